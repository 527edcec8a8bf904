//! The profile of G71/G72/G73: the blocks `N ns … N nf` read as turning-plane geometry
//! (`docs/dialects/mazatrol-eia.md` §11).
//!
//! The blocks are read, not executed: each may hold G00/G01/G02/G03, G90/G91, X/U (diameters under
//! G123.1), Z/W, R or I/K (radii, I and K relative to the start), F, S, T and N; anything else is
//! refused. The motion mode and the distance mode start as they are at the cycle block and are
//! modal within the profile. The result is the list of [`Step`]s from the start point A, in the
//! (z, x-radius) plane of `turning.rs`.

use crate::turning::{Step, Zx};
use stanok_canon::Span;
use stanok_geom::centre_from_radius;
use stanok_syntax::{Address, Block, Word};

/// The modes a profile starts with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfileModes {
    /// G91 in force.
    pub incremental: bool,
    /// X and U are diameters (G123.1).
    pub x_diameter: bool,
    /// The motion mode × 10 (0, 10, 20, 30).
    pub motion: u32,
    /// How far an arc's end may miss its circle, mm.
    pub arc_tolerance: f64,
}

/// A refusal in a profile block: the message and the block's span.
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileError {
    /// What is wrong.
    pub message: String,
    /// The block.
    pub span: Span,
}

fn fail<T>(block: &Block, m: impl Into<String>) -> Result<T, ProfileError> {
    Err(ProfileError {
        message: m.into(),
        span: block.span(),
    })
}

/// The value of a word: `Ok(None)` when it is vacant (the word is dropped).
pub type WordValue<'a> = dyn FnMut(&Block, &Word) -> Result<Option<f64>, ProfileError> + 'a;

/// Reads `blocks` (ns … nf) from the start point `a`.
pub fn read_profile<'b>(
    blocks: impl IntoIterator<Item = &'b Block>,
    a: Zx,
    mut modes: ProfileModes,
    value: &mut WordValue<'_>,
) -> Result<Vec<Step>, ProfileError> {
    let mut at = a;
    let mut out = Vec::new();
    for b in blocks {
        if b.statement.is_some() || !b.assignments.is_empty() {
            return fail(b, "a profile block cannot hold a macro statement");
        }
        let mut x: Option<(f64, bool)> = None;
        let mut z: Option<(f64, bool)> = None;
        let (mut r, mut i, mut k) = (None, None, None);
        for w in &b.words {
            let Address::Letter(l) = w.address else {
                return fail(
                    b,
                    "a profile block holds only G, X, Z, U, W, R, I, K, F, S, T",
                );
            };
            let Some(v) = value(b, w)? else {
                continue;
            };
            match l {
                b'G' => {
                    let code = (v * 10.0).round() as u32;
                    match code {
                        0 | 10 | 20 | 30 => modes.motion = code,
                        900 => modes.incremental = false,
                        910 => modes.incremental = true,
                        _ => {
                            return fail(
                                b,
                                format!("G{v} is not allowed in a turning cycle's profile"),
                            )
                        }
                    }
                }
                b'X' => x = Some((v, false)),
                b'U' => x = Some((v, true)),
                b'Z' => z = Some((v, false)),
                b'W' => z = Some((v, true)),
                b'R' => r = Some(v),
                b'I' => i = Some(v),
                b'K' => k = Some(v),
                b'F' | b'S' | b'T' | b'O' => {}
                b'M' => return fail(b, "M codes are not allowed in a turning cycle's profile"),
                other => {
                    return fail(
                        b,
                        format!(
                            "{} is not allowed in a turning cycle's profile",
                            other as char
                        ),
                    )
                }
            }
        }
        if x.is_none() && z.is_none() {
            continue;
        }
        let xs = if modes.x_diameter { 0.5 } else { 1.0 };
        let end_x = match x {
            Some((v, inc)) if inc || modes.incremental => at[1] + v * xs,
            Some((v, _)) => v * xs,
            None => at[1],
        };
        let end_z = match z {
            Some((v, inc)) if inc || modes.incremental => at[0] + v,
            Some((v, _)) => v,
            None => at[0],
        };
        let end = [end_z, end_x];
        match modes.motion {
            0 => out.push(Step::Rapid(end)),
            10 => out.push(Step::Feed(end)),
            _ => {
                let ccw = modes.motion == 30;
                let centre = if let Some(r) = r {
                    centre_from_radius(at, end, r.abs(), ccw, r < 0.0, modes.arc_tolerance)
                        .map_err(|e| ProfileError {
                            message: format!("the arc of the profile: {e}"),
                            span: b.span(),
                        })?
                } else {
                    [at[0] + k.unwrap_or(0.0), at[1] + i.unwrap_or(0.0)]
                };
                let r0 = (at[0] - centre[0]).hypot(at[1] - centre[1]);
                let r1 = (end[0] - centre[0]).hypot(end[1] - centre[1]);
                if r0 < 1e-9 || (r0 - r1).abs() > modes.arc_tolerance {
                    return fail(
                        b,
                        format!(
                            "the arc of the profile: start radius {r0:.4} and end radius {r1:.4} differ by more than {}",
                            modes.arc_tolerance
                        ),
                    );
                }
                out.push(Step::Arc {
                    to: end,
                    centre,
                    ccw,
                });
            }
        }
        at = end;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use stanok_syntax::{parse, Dialect, Value};

    fn number(b: &Block, w: &Word) -> Result<Option<f64>, ProfileError> {
        match w.value {
            Value::Number(v) => Ok(Some(v)),
            _ => fail(b, "expression"),
        }
    }

    fn modes() -> ProfileModes {
        ProfileModes {
            incremental: false,
            x_diameter: true,
            motion: 0,
            arc_tolerance: 0.01,
        }
    }

    #[test]
    fn the_example_profile() {
        let text = "N20 G00 X30.\nN21 G01 Z-20. F0.1\nN22 X40. Z-25.\nN23 Z-40.\nN24 G02 X50. Z-45. R5.\nN25 G01 X58.\nN26 Z-60.\n";
        let (p, d) = parse(text, Dialect::Mazatrol);
        assert!(d.is_empty());
        let steps = read_profile(&p.blocks, [2.0, 31.0], modes(), &mut number).unwrap();
        assert_eq!(steps[0], Step::Rapid([2.0, 15.0]));
        assert_eq!(steps[1], Step::Feed([-20.0, 15.0]));
        assert_eq!(steps[2], Step::Feed([-25.0, 20.0]));
        match steps[4] {
            Step::Arc { to, centre, ccw } => {
                assert_eq!(to, [-45.0, 25.0]);
                assert!((centre[0] + 40.0).abs() < 1e-9 && (centre[1] - 25.0).abs() < 1e-9);
                assert!(!ccw);
            }
            s => panic!("{s:?}"),
        }
        assert_eq!(steps[6], Step::Feed([-60.0, 29.0]));
        // It is the profile turning.rs's test uses.
        let rough = crate::turning::g71(
            [2.0, 31.0],
            &steps,
            crate::turning::StockRemoval {
                depth: 2.0,
                retract: 0.5,
                allowance_x: 0.2,
                allowance_z: 0.1,
            },
        )
        .unwrap();
        assert_eq!(rough.len(), 7 * 4 + 1 + 6 + 1);
    }

    #[test]
    fn incremental_and_i_k_arcs() {
        let text = "G01 U-10. W-5.\nG03 U10. W-5. I0 K-5.\n";
        let (p, _) = parse(text, Dialect::Mazatrol);
        let steps = read_profile(&p.blocks, [0.0, 20.0], modes(), &mut number).unwrap();
        assert_eq!(steps[0], Step::Feed([-5.0, 15.0]));
        assert_eq!(
            steps[1],
            Step::Arc {
                to: [-10.0, 20.0],
                centre: [-10.0, 15.0],
                ccw: true
            }
        );
    }

    #[test]
    fn refusals() {
        for text in ["G04 X1.", "M08", "G01 Y1.", "#1=2", "G02 X10. Z0 I3."] {
            let (p, _) = parse(text, Dialect::Mazatrol);
            assert!(
                read_profile(&p.blocks, [0.0, 20.0], modes(), &mut number).is_err(),
                "{text}"
            );
        }
    }
}
