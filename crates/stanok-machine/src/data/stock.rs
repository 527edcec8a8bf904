//! `[stock]`: what the stock-removal simulation needs from the machine (`machines/README.md`).
//!
//! ```toml
//! [stock]
//! shape = "box:X0,Y0,Z-30:X100,Y80,Z0"   # the --stock syntax (box, cylinder, file.stl); optional
//! frame = "work"                          # "work" (default) | "machine": coordinates of `shape`
//! resolution = 0.1                        # model cell size, mm (default 0.1, coarsened for big stocks)
//! fixture_z = -30.0                       # top of the fixture/table, machine Z, mm
//! ```

use super::Invalid;
use crate::control::{toml_float, toml_string};
use serde::{Deserialize, Serialize};
use stanok_stock::spec::{StockFrame, StockShape};
use std::fmt::Write;
use toml::Spanned;

/// The `[stock]` section, validated.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StockData {
    /// The raw stock (None: only from the command line).
    pub shape: Option<StockShape>,
    /// As written, for writing back.
    #[serde(skip)]
    pub shape_text: Option<String>,
    /// Coordinates of `shape`.
    pub frame: StockFrame,
    /// Model cell size, mm.
    pub resolution: Option<f64>,
    /// Top of the fixture/table, machine Z, mm: no part of the tool or holder may go below it.
    pub fixture_z: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawStock {
    shape: Option<Spanned<String>>,
    frame: Option<Spanned<String>>,
    resolution: Option<Spanned<f64>>,
    fixture_z: Option<Spanned<f64>>,
}

impl RawStock {
    pub(crate) fn validate(raw: &Spanned<RawStock>) -> Result<StockData, Invalid> {
        let r = raw.get_ref();
        let shape = match &r.shape {
            None => None,
            Some(s) => Some(
                StockShape::parse(s.get_ref())
                    .map_err(|e| (format!("[stock] shape: {e}"), s.span()))?,
            ),
        };
        let frame = match &r.frame {
            None => StockFrame::Work,
            Some(f) => {
                StockFrame::parse(f.get_ref()).map_err(|e| (format!("[stock] {e}"), f.span()))?
            }
        };
        let resolution = match &r.resolution {
            None => None,
            Some(v) => {
                let x = *v.get_ref();
                if !(0.001..=100.0).contains(&x) {
                    return Err((
                        format!("[stock] resolution must be 0.001 … 100 mm, not {x}"),
                        v.span(),
                    ));
                }
                Some(x)
            }
        };
        let fixture_z = match &r.fixture_z {
            None => None,
            Some(v) if v.get_ref().is_finite() => Some(*v.get_ref()),
            Some(v) => {
                return Err((
                    format!(
                        "[stock] fixture_z must be a finite number, not {}",
                        v.get_ref()
                    ),
                    v.span(),
                ))
            }
        };
        Ok(StockData {
            shape,
            shape_text: r.shape.as_ref().map(|s| s.get_ref().clone()),
            frame,
            resolution,
            fixture_z,
        })
    }
}

/// The section as TOML (sparse).
pub(crate) fn write(out: &mut String, s: &StockData) {
    out.push_str("\n[stock]\n");
    if let Some(t) = &s.shape_text {
        let _ = writeln!(out, "shape = {}", toml_string(t));
    }
    if s.frame == StockFrame::Machine {
        out.push_str("frame = \"machine\"\n");
    }
    if let Some(r) = s.resolution {
        let _ = writeln!(out, "resolution = {}", toml_float(r));
    }
    if let Some(z) = s.fixture_z {
        let _ = writeln!(out, "fixture_z = {}", toml_float(z));
    }
}
