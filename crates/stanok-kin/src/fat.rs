//! The Balt-System characterization line `FAT=m,tm,f3,f4,s,ts,f7,f8` (PGCFIL section 5,
//! cvu-five-axis.md §4) mapped to our rotary-chain model.
//!
//! Fields: m / s = the main and the dependent rotary axis (A, B or C); tm / ts = 0 on the tool,
//! 1 on the part; f3, f4, f7, f8 = the "skew" offsets of tables 2.2–2.4 (empty = 0).
//!
//! Mapping (spec §5.2–§5.6; GOST 23597-79: an angle is the motion of the tool relative to the
//! part, so a part-side axis turns the table by R(−θ): it gets `sign = −1` here):
//!
//! | (tm, ts) | chain | points |
//! |---|---|---|
//! | TT (0, 0) | head: m outer, s inner | d_m = (f3, f4, 0), d_s = (0, 0, f7): q_m = −d_s − d_m, q_s = −d_s relative to the gauge point |
//! | DD (1, 1) | table: m outer (bed), s inner (workpiece) | c_m: A (0, f3, f4), B (f3, 0, f4); c_s: A (0, f7, f8), B (f7, 0, f8), C (f7, f8, 0) (AMB-3 proposal) |
//! | DT (1, 0) | table m + head s | c_m: A (0, f3, f4), B (f3, 0, f4), C (f3, f4, 0); the head axis passes through the gauge point |
//!
//! Validation (spec §4.4, checked in this order): a field count other than 8 or a name other than
//! A/B/C, m = s, tm/ts not 0/1 → 116; (0, 1) → 142; TT with dependent C → 143; DD with main C →
//! 144; DT with dependent C → 145; DT with a non-zero f7/f8 or TT with a non-zero f8 → 116.

use crate::{Carrier, FiveAxis, KinError, RotaryAxis};

/// A FAT line that the control refuses: the manual's error number and why.
#[derive(Debug, Clone, PartialEq)]
pub struct FatError {
    /// The Balt-System error code (116, 142, 143, 144, 145).
    pub code: u32,
    /// What is wrong.
    pub message: String,
}

fn bad(code: u32, message: impl Into<String>) -> FatError {
    FatError {
        code,
        message: message.into(),
    }
}

fn direction(name: char) -> [f64; 3] {
    match name {
        'A' => [1.0, 0.0, 0.0],
        'B' => [0.0, 1.0, 0.0],
        _ => [0.0, 0.0, 1.0],
    }
}

/// The machine a FAT line describes (the text after `FAT=`), base vector +Z.
pub fn from_fat(line: &str) -> Result<FiveAxis, FatError> {
    let fields: Vec<&str> = line.split(',').map(str::trim).collect();
    if fields.len() != 8 {
        return Err(bad(
            116,
            format!("FAT has {} fields, 8 expected", fields.len()),
        ));
    }
    let name = |s: &str| -> Result<char, FatError> {
        match s.to_ascii_uppercase().as_str() {
            "A" => Ok('A'),
            "B" => Ok('B'),
            "C" => Ok('C'),
            _ => Err(bad(116, format!("rotary axis name {s:?} is not A, B or C"))),
        }
    };
    let place = |s: &str| -> Result<u8, FatError> {
        match s {
            "0" => Ok(0),
            "1" => Ok(1),
            _ => Err(bad(
                116,
                format!("placement {s:?} is not 0 (tool) or 1 (part)"),
            )),
        }
    };
    let num = |s: &str| -> Result<f64, FatError> {
        if s.is_empty() {
            return Ok(0.0);
        }
        s.parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| bad(116, format!("offset {s:?} is not a number")))
    };
    let (m, tm) = (name(fields[0])?, place(fields[1])?);
    let (f3, f4) = (num(fields[2])?, num(fields[3])?);
    let (s, ts) = (name(fields[4])?, place(fields[5])?);
    let (f7, f8) = (num(fields[6])?, num(fields[7])?);
    if m == s {
        return Err(bad(116, "the main and the dependent axis are the same"));
    }
    let axes = match (tm, ts) {
        (0, 1) => {
            return Err(bad(
                142,
                "configuration 0-1 (main on the tool, dependent on the part) is impossible",
            ))
        }
        (0, 0) if s == 'C' => {
            return Err(bad(
                143,
                "both axes on the tool: C cannot be the dependent axis",
            ))
        }
        (1, 1) if m == 'C' => {
            return Err(bad(144, "both axes on the part: C cannot be the main axis"))
        }
        (1, 0) if s == 'C' => {
            return Err(bad(
                145,
                "main on the part, dependent on the tool: C cannot be the dependent axis",
            ))
        }
        (1, 0) if f7 != 0.0 || f8 != 0.0 => {
            return Err(bad(
                116,
                "the dependent (tool) axis of a DT machine has no skew: f7 and f8 must be 0",
            ))
        }
        (0, 0) if f8 != 0.0 => return Err(bad(116, "field 8 of a TT machine must be 0")),
        (0, 0) => {
            let d_m = [f3, f4, 0.0];
            let d_s = [0.0, 0.0, f7];
            vec![
                RotaryAxis::new(
                    m,
                    Carrier::Head,
                    direction(m),
                    [-d_s[0] - d_m[0], -d_s[1] - d_m[1], -d_s[2] - d_m[2]],
                ),
                RotaryAxis::new(s, Carrier::Head, direction(s), [0.0, 0.0, -f7]),
            ]
        }
        (1, 1) => {
            let c_m = match m {
                'A' => [0.0, f3, f4],
                _ => [f3, 0.0, f4],
            };
            let c_s = match s {
                'A' => [0.0, f7, f8],
                'B' => [f7, 0.0, f8],
                _ => [f7, f8, 0.0],
            };
            vec![table_axis(m, c_m), table_axis(s, c_s)]
        }
        _ => {
            let c_m = match m {
                'A' => [0.0, f3, f4],
                'B' => [f3, 0.0, f4],
                _ => [f3, f4, 0.0],
            };
            vec![
                RotaryAxis::new(s, Carrier::Head, direction(s), [0.0; 3]),
                table_axis(m, c_m),
            ]
        }
    };
    FiveAxis::new(axes, [0.0, 0.0, 1.0]).map_err(|e: KinError| bad(116, e.to_string()))
}

/// A part-side axis: GOST angles are tool-relative, so the table turns by −θ.
fn table_axis(name: char, point: [f64; 3]) -> RotaryAxis {
    let mut a = RotaryAxis::new(name, Carrier::Table, direction(name), point);
    a.sign = -1.0;
    a
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Kinematics;
    use stanok_canon::Pose;

    fn q(fat: &str, a: f64, c: f64) -> [f64; 3] {
        let k = from_fat(fat).unwrap().with_tool_length(100.0);
        let j = k.inverse(&Pose { a, c, ..Pose::ZERO }).unwrap();
        [j[0], j[1], j[2]]
    }

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|i| (a[i] - b[i]).abs() < 1e-6)
    }

    #[test]
    fn oracle_o1_every_fat_variant() {
        // cvu-five-axis.md §8 O1: tip at the part zero, A30 C50, L = 100.
        for (fat, want) in [
            ("C,0,0,0,A,0,0,0", [38.302222, -32.139380, 86.602540]),
            ("C,0,0,20,A,0,-150,0", [111.076444, -73.204203, 66.506351]),
            ("A,1,0,-50,C,1,10,0", [3.572124, 31.634139, 89.471048]),
            ("C,1,10,0,A,0,0,0", [3.572124, -42.339556, 86.602540]),
        ] {
            let got = q(fat, 30.0, 50.0);
            assert!(close(got, want), "{fat}: {got:?}");
            // At zero angles every variant is plain length compensation.
            assert!(close(q(fat, 0.0, 0.0), [0.0, 0.0, 100.0]), "{fat}");
            // The same tool vector on every variant: u = Rz(50)·Rx(30)·ez.
            let t = from_fat(fat).unwrap().tool_vector_at(&Pose {
                a: 30.0,
                c: 50.0,
                ..Pose::ZERO
            });
            assert!(
                close(t, [0.383022221559, -0.321393804843, 0.866025403784]),
                "{fat}: {t:?}"
            );
        }
    }

    #[test]
    fn validation_vectors_of_the_spec() {
        for (fat, code) in [
            ("C,0,,,A,0,,", 0),
            ("C,1,,,A,0,,", 0),
            ("A,1,,,C,1,,", 0),
            ("A,0,,,B,0,,", 0),
            ("B,1,,,A,1,,", 0),
            ("A,1,,,B,0,,", 0),
            ("A,0,,,C,0,,", 143),
            ("B,0,,,C,0,,", 143),
            ("C,1,,,A,1,,", 144),
            ("A,1,,,C,0,,", 145),
            ("C,0,,,A,1,,", 142),
            ("D,0,,,A,0,,", 116),
            ("C,1,5,5,A,0,1,0", 116),
            ("C,0,1,2,A,0", 116),
        ] {
            let got = from_fat(fat).err().map_or(0, |e| e.code);
            assert_eq!(got, code, "{fat}");
        }
    }
}
