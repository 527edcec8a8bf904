//! A dialect's table of codes: for each G (or other letter) code its value, its name as a
//! programmer writes it, its modal group and what executes it — declared once, in one place per
//! front end, with [`code_table!`].
//!
//! Values are the code × 10 (`Words::g` holds them so: G33 = 330, G43.4 = 434), so that decimal
//! codes are integers. The macro gives each code a named constant (`G33`), the table itself (for
//! listings and tests), and a lookup compiled to a `match` on the value — as fast as the hand
//! written match it replaces, on the per-block path.

/// One code of a dialect.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Code<G, H> {
    /// The value × 10.
    pub code: u32,
    /// As written: `G33`, `G43.4`.
    pub name: &'static str,
    /// Its modal group (the front end's enum).
    pub group: G,
    /// What executes it (the front end's enum).
    pub handler: H,
}

/// Declares a dialect's code table (module doc):
///
/// ```text
/// code_table! {
///     /// The table.
///     pub G_CODES, pub fn g_code -> Code<Group, Handler>;
///     /// G0: rapid.
///     G0 = 0, "G0", Group::Motion, Handler::Straight;
///     …
/// }
/// ```
///
/// expands to `pub const G0: u32 = 0;` for every code, `pub const G_CODES: &[Code<Group,
/// Handler>]` in the written order, and `pub fn g_code(code: u32) -> Option<Code<Group,
/// Handler>>`.
#[macro_export]
macro_rules! code_table {
    (
        $(#[$tmeta:meta])*
        $tvis:vis $table:ident, $fvis:vis fn $lookup:ident -> Code<$group:ty, $handler:ty>;
        $(
            $(#[$cmeta:meta])*
            $name:ident = $value:literal, $text:literal, $grp:expr, $h:expr;
        )*
    ) => {
        $(
            $(#[$cmeta])*
            #[allow(dead_code)]
            $tvis const $name: u32 = $value;
        )*

        $(#[$tmeta])*
        #[allow(dead_code)]
        $tvis const $table: &[$crate::codes::Code<$group, $handler>] = &[
            $(
                $crate::codes::Code {
                    code: $value,
                    name: $text,
                    group: $grp,
                    handler: $h,
                },
            )*
        ];

        /// The code with this value (× 10), if the dialect has it.
        #[inline(always)]
        #[allow(dead_code)]
        $fvis fn $lookup(code: u32) -> Option<$crate::codes::Code<$group, $handler>> {
            match code {
                $(
                    $value => Some($crate::codes::Code {
                        code: $value,
                        name: $text,
                        group: $grp,
                        handler: $h,
                    }),
                )*
                _ => None,
            }
        }
    };
}

#[cfg(test)]
mod tests {
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    enum Group {
        Motion,
        Plane,
    }

    code_table! {
        /// A small table.
        TABLE, fn lookup -> Code<Group, u8>;
        /// Rapid.
        G0 = 0, "G0", Group::Motion, 1;
        G18 = 180, "G18", Group::Plane, 2;
        G33_1 = 331, "G33.1", Group::Motion, 3;
    }

    #[test]
    fn constants_table_and_lookup_agree() {
        assert_eq!((G0, G18, G33_1), (0, 180, 331));
        assert_eq!(TABLE.len(), 3);
        for c in TABLE {
            assert_eq!(lookup(c.code), Some(*c));
        }
        assert_eq!(lookup(330), None);
        assert_eq!(lookup(G33_1).map(|c| c.name), Some("G33.1"));
    }
}
