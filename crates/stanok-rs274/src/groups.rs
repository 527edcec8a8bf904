//! RS274/NGC's modal groups: which group each G code belongs to (`codes.rs`), and the block's G
//! codes sorted into them with LinuxCNC's reading errors (an unknown code, two of one group).

use crate::codes::*;
use crate::ctx::Ctx;
use stanok_canon::Diagnostic;
use stanok_syntax::ColSpan;

/// LinuxCNC's modal groups (the ones this module distinguishes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Group {
    /// Group 0: G4, G10, G28, G30, G52, G53, G92 …
    NonModal,
    /// Group 1.
    Motion,
    /// Group 2.
    Plane,
    /// Group 3.
    Distance,
    /// Group 4 (LinuxCNC's "arc distance").
    ArcDistance,
    /// Group 5.
    FeedMode,
    /// Group 6.
    Units,
    /// Group 7.
    CutterComp,
    /// Group 8.
    ToolLength,
    /// Group 10.
    Retract,
    /// Group 12.
    CoordSystem,
    /// Group 13.
    PathControl,
    /// Group 14.
    SpindleMode,
    /// Group 15.
    LatheDiameter,
}

/// Group of a G code (×10), or None if LinuxCNC does not know it.
#[inline(always)]
pub(crate) fn group_of(code: u32) -> Option<Group> {
    g_code(code).map(|c| c.group)
}

pub(crate) fn g_name(code: u32) -> String {
    if let Some(c) = g_code(code) {
        return c.name.to_string();
    }
    if code.is_multiple_of(10) {
        format!("G{}", code / 10)
    } else {
        format!("G{}.{}", code / 10, code % 10)
    }
}

/// Number of groups in [`Group`].
pub(crate) const GROUPS: usize = 14;
/// "No code of this group in the block".
pub(crate) const NO_CODE: u32 = u32::MAX;

/// The G codes of one block, one per group (plain arrays: this runs for every block). A code's
/// span stays in the block's words (`at` indexes `Words::g`): copying fourteen spans in and out
/// of every block cost more than the whole lookup.
pub(crate) struct GCodes {
    pub(crate) code: [u32; GROUPS],
    /// Index of the group's code in `Words::g` (valid where `code` is not `NO_CODE`).
    pub(crate) at: [u32; GROUPS],
    /// G53 travels with the motion group in LinuxCNC ("G53 may share a line with G0/G1").
    pub(crate) g53: Option<ColSpan>,
}

impl GCodes {
    pub(crate) fn new() -> Self {
        GCodes {
            code: [NO_CODE; GROUPS],
            at: [0; GROUPS],
            g53: None,
        }
    }

    pub(crate) fn get(&self, g: Group, cx: &Ctx<'_>) -> Option<(u32, ColSpan)> {
        let c = self.code[g as usize];
        (c != NO_CODE).then(|| (c, cx.words.g[self.at[g as usize] as usize].1))
    }
}

/// Sorts the block's G codes into groups, into `g` (fresh from `GCodes::new`). An out-parameter:
/// returned inside a `Result` the table was copied twice per block.
#[inline(always)]
pub(crate) fn classify(cx: &Ctx<'_>, g: &mut GCodes) -> Result<(), Diagnostic> {
    for (i, &(code, span)) in cx.words.g.iter().enumerate() {
        let Some(group) = group_of(code) else {
            return Err(cx.err(
                "rs274::unknown-g-code",
                format!("Unknown g code used: {}", g_name(code)),
                span,
            ));
        };
        // G53 is group 0 too: it travels with the motion, but shares the group with G4, G10 ….
        let prev = if code == G53 {
            g.code[Group::NonModal as usize]
        } else if group == Group::NonModal && g.g53.is_some() {
            G53
        } else {
            g.code[group as usize]
        };
        if code == G53 && prev == NO_CODE {
            g.g53 = Some(span);
            continue;
        }
        if prev != NO_CODE {
            return Err(cx
                .err(
                    "rs274::two-g-codes-same-group",
                    "Two g codes used from same modal group",
                    span,
                )
                .with_note(format!("{} and {}", g_name(prev), g_name(code))));
        }
        g.code[group as usize] = code;
        g.at[group as usize] = i as u32;
    }
    Ok(())
}
