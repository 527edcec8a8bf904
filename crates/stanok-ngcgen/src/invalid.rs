//! Invalid variants: one block written wrong at the current point of a valid program, in a way
//! whose first error LinuxCNC names (a message, and the block it stops at). The runner then checks
//! that Stanok stops at the same block with the same message and has executed nothing of it.

use crate::Gen;

/// The wrong blocks: (what is wrong, the block). Each needs nothing of the state but G94 feed,
/// G17 and G90 where it says so (the line before sets them).
const WRONG: [(&str, &str); 30] = [
    ("invalid: tool not in table", "T77 M6"),
    ("invalid: H not in table", "G43 H77"),
    ("invalid: unclosed bracket", "G1 X[1 + 2"),
    ("invalid: unknown M code", "M123"),
    ("invalid: sqrt of negative", "G1 X[SQRT[-1]]"),
    ("invalid: acos out of range", "G1 X[ACOS[2]]"),
    ("invalid: unmatched endif", "o999 endif"),
    ("invalid: comp tool missing", "G41 D99"),
    ("invalid: G10 L3", "G10 L3 P1"),
    ("invalid: undefined named parameter", "G1 X#<nosuch>"),
    ("invalid: canned cycle Q missing", "G83 X1 Y1 Z-1 R2"),
    ("invalid: arc without centre", "G2 X1 Y1"),
    ("invalid: two motion codes", "G1 X1 G0 Y2"),
    ("invalid: zero feed", "G1 F0 X1"),
    ("invalid: dwell without P", "G4"),
    ("invalid: unknown G code", "G7.5"),
    ("invalid: two M codes of a group", "M3 M4 S10"),
    ("invalid: repeated word", "G1 X1 X2"),
    ("invalid: U axis", "G1 U1"),
    ("invalid: divide by zero", "#1 = [1 / 0]"),
    ("invalid: G10 L2 P out of range", "G10 L2 P10 X0"),
    ("invalid: G53 incremental", "G53 G91 G0 X1"),
    ("invalid: G92 without axes", "G92"),
    ("invalid: unused H", "G1 X1 H2"),
    ("invalid: unused R", "G0 X1 R2"),
    ("invalid: ln of zero", "G1 X[LN[0]]"),
    (
        "invalid: negative to fractional power",
        "G1 X[[0 - 2] ** 0.5]",
    ),
    (
        "invalid: probe to start point",
        "G38.2 X#<_x> Y#<_y> Z#<_z> F10",
    ),
    ("invalid: M62 without P", "M62"),
    ("invalid: G43.2 without H", "G43.2"),
];

/// Writes a wrong block (after one that sets G94, G17, G90, a feed); returns what is wrong.
pub fn corrupt(g: &mut Gen) -> Option<&'static str> {
    if g.st.busy {
        return None;
    }
    let (what, block) = WRONG[g.rng.below(WRONG.len() as u64) as usize];
    g.line("G94 G17 G90 F100");
    g.st.feed_mode = 94;
    g.st.plane = 17;
    g.st.absolute = true;
    g.feat(what);
    g.feat("invalid: any");
    g.line(block);
    Some(what)
}
