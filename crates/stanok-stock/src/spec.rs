//! The stock as the user names it: `--stock` and the `[stock]` section of machine data.
//!
//! ```text
//! box:X0,Y0,Z-30:X100,Y80,Z0          two opposite corners
//! cylinder:Z-80:D50,Z0                 axis along Z through X0 Y0: one end face, then the
//! cylinder:X10,Y20,Z-80:D50,Z0,B20     diameter D and the other end (B = bore diameter)
//! part.stl                             a closed triangle mesh (binary or ASCII STL)
//! ```
//! Words are a letter and a number, separated by commas; groups by colons; blanks are ignored,
//! letters may be lower case. Coordinates are in the stock's frame ([`StockFrame`]): the
//! program's work coordinates by default, machine coordinates on request.

use serde::Serialize;
use std::path::PathBuf;

/// The shape of the raw stock, stock frame, mm.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum StockShape {
    /// An axis-parallel box.
    Box {
        /// Smallest X, Y, Z.
        min: [f64; 3],
        /// Largest X, Y, Z.
        max: [f64; 3],
    },
    /// A cylinder along Z (a lathe's bar; a round blank on a mill).
    Cylinder {
        /// X, Y of the axis.
        centre: [f64; 2],
        /// Lower and upper Z.
        z: [f64; 2],
        /// Outer diameter.
        diameter: f64,
        /// Bore diameter (0 = solid).
        bore: f64,
    },
    /// A closed triangle mesh read from an STL file.
    Mesh {
        /// The file.
        path: PathBuf,
    },
}

/// Which coordinates the stock is given in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum StockFrame {
    /// The work coordinates the program starts in (the machine data's active zero offset).
    #[default]
    Work,
    /// Machine coordinates (the workpiece-fixed frame of a rotary table at zero).
    Machine,
}

impl StockFrame {
    /// `work` or `machine`.
    pub fn parse(text: &str) -> Result<StockFrame, String> {
        match text.trim().to_ascii_lowercase().as_str() {
            "work" => Ok(StockFrame::Work),
            "machine" => Ok(StockFrame::Machine),
            other => Err(format!(
                "the stock frame is work or machine, not \"{other}\""
            )),
        }
    }
}

/// Words of one group: letter → value, each letter at most once.
fn words(group: &str, allowed: &str) -> Result<Vec<(char, f64)>, String> {
    let mut out: Vec<(char, f64)> = Vec::new();
    for w in group.split(',') {
        let w: String = w.chars().filter(|c| !c.is_whitespace()).collect();
        let mut chars = w.chars();
        let Some(letter) = chars.next().map(|c| c.to_ascii_uppercase()) else {
            return Err(format!("an empty word in \"{group}\""));
        };
        if !allowed.contains(letter) {
            return Err(format!(
                "\"{w}\": the words here are {}",
                allowed
                    .chars()
                    .map(String::from)
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
        let v: f64 = chars
            .as_str()
            .parse()
            .ok()
            .filter(|v: &f64| v.is_finite())
            .ok_or_else(|| format!("\"{w}\": {letter} needs a number"))?;
        if out.iter().any(|(l, _)| *l == letter) {
            return Err(format!("{letter} given twice in \"{group}\""));
        }
        out.push((letter, v));
    }
    Ok(out)
}

fn get(ws: &[(char, f64)], letter: char) -> Option<f64> {
    ws.iter().find(|(l, _)| *l == letter).map(|(_, v)| *v)
}

/// Largest extent of a stock along any axis, mm (a bound on memory with the resolution).
pub const MAX_EXTENT: f64 = 10_000.0;

impl StockShape {
    /// Parses the `--stock` syntax (module doc).
    pub fn parse(text: &str) -> Result<StockShape, String> {
        let t = text.trim();
        let lower = t.to_ascii_lowercase();
        let shape = if let Some(rest) = lower.strip_prefix("box:") {
            let groups: Vec<&str> = rest.split(':').collect();
            if groups.len() != 2 {
                return Err("box: wants two corners, box:X0,Y0,Z-30:X100,Y80,Z0".into());
            }
            let a = words(groups[0], "XYZ")?;
            let b = words(groups[1], "XYZ")?;
            let mut min = [0.0; 3];
            let mut max = [0.0; 3];
            for (k, l) in ['X', 'Y', 'Z'].into_iter().enumerate() {
                let (Some(p), Some(q)) = (get(&a, l), get(&b, l)) else {
                    return Err(format!("box: each corner needs X, Y and Z ({l} missing)"));
                };
                min[k] = p.min(q);
                max[k] = p.max(q);
                if max[k] - min[k] <= 0.0 {
                    return Err(format!("box: the corners have the same {l}"));
                }
            }
            StockShape::Box { min, max }
        } else if let Some(rest) = lower.strip_prefix("cylinder:") {
            let groups: Vec<&str> = rest.split(':').collect();
            if groups.len() != 2 {
                return Err(
                    "cylinder: wants an end face and the diameter with the other end, \
                     cylinder:Z-80:D50,Z0 (X, Y of the axis and a bore B optional)"
                        .into(),
                );
            }
            let a = words(groups[0], "XYZ")?;
            let b = words(groups[1], "DZB")?;
            let (Some(z0), Some(z1)) = (get(&a, 'Z'), get(&b, 'Z')) else {
                return Err("cylinder: both ends need a Z".into());
            };
            let Some(diameter) = get(&b, 'D').filter(|d| *d > 0.0) else {
                return Err("cylinder: needs a diameter D > 0".into());
            };
            let bore = get(&b, 'B').unwrap_or(0.0);
            if !(0.0..diameter).contains(&bore) {
                return Err("cylinder: the bore B must be at least 0 and less than D".into());
            }
            if z0 == z1 {
                return Err("cylinder: the ends have the same Z".into());
            }
            StockShape::Cylinder {
                centre: [get(&a, 'X').unwrap_or(0.0), get(&a, 'Y').unwrap_or(0.0)],
                z: [z0.min(z1), z0.max(z1)],
                diameter,
                bore,
            }
        } else if lower.ends_with(".stl") {
            StockShape::Mesh {
                path: PathBuf::from(t),
            }
        } else {
            return Err(format!(
                "\"{t}\" is not a stock: box:X0,Y0,Z-30:X100,Y80,Z0, cylinder:Z-80:D50,Z0 or a file.stl"
            ));
        };
        if let Some(e) = shape.extent() {
            if e > MAX_EXTENT {
                return Err(format!(
                    "the stock is {e:.0} mm long; at most {MAX_EXTENT:.0} mm"
                ));
            }
        }
        Ok(shape)
    }

    /// Largest side of its box (None for a mesh, known only once read).
    pub fn extent(&self) -> Option<f64> {
        match self {
            StockShape::Box { min, max } => {
                Some((0..3).map(|k| max[k] - min[k]).fold(0.0, f64::max))
            }
            StockShape::Cylinder { z, diameter, .. } => Some((z[1] - z[0]).max(*diameter)),
            StockShape::Mesh { .. } => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_documented_forms_parse() {
        assert_eq!(
            StockShape::parse("box:X0,Y0,Z-30:X100,Y80,Z0"),
            Ok(StockShape::Box {
                min: [0.0, 0.0, -30.0],
                max: [100.0, 80.0, 0.0]
            })
        );
        assert_eq!(
            StockShape::parse(" box: x100, y80 ,z0 : X0,Y0,Z-30 "),
            StockShape::parse("box:X0,Y0,Z-30:X100,Y80,Z0")
        );
        assert_eq!(
            StockShape::parse("cylinder:X10,Y20,Z-80:D50,Z0,B20"),
            Ok(StockShape::Cylinder {
                centre: [10.0, 20.0],
                z: [-80.0, 0.0],
                diameter: 50.0,
                bore: 20.0
            })
        );
        assert!(matches!(
            StockShape::parse("Part.STL"),
            Ok(StockShape::Mesh { .. })
        ));
    }

    #[test]
    fn bad_stocks_say_why() {
        for (text, why) in [
            ("box:X0,Y0:X1,Y1,Z1", "Z missing"),
            ("box:X0,Y0,Z0:X1,Y1,Z0", "same Z"),
            ("box:X0,Y0,Z0,X1:X1,Y1,Z1", "X given twice"),
            ("box:X0,Y0,Zq:X1,Y1,Z1", "Z needs a number"),
            ("box:X0,Y0,Z0:X1,Y1,Z1:X2", "two corners"),
            ("cylinder:Z0:Z10", "diameter"),
            ("cylinder:Z0:D10,Z10,B12", "bore"),
            ("cylinder:Z0:D10,Z10,Q1", "the words here are D, Z, B"),
            ("sphere:R10", "not a stock"),
            ("box:X0,Y0,Z0:X1e9,Y1,Z1", "at most"),
            ("box:X0,Y0,Z0:Xinf,Y1,Z1", "needs a number"),
        ] {
            let e = StockShape::parse(text).unwrap_err();
            assert!(e.contains(why), "{text}: {e}");
        }
    }
}
