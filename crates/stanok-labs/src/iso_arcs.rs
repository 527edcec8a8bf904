//! Arcs and helices of the word-address lab dialects (GOST-20999 §4.5, MC2101 §3.10).
//!
//! All geometry is in machine coordinates (the work frame is a pure translation, and no length
//! correction may change inside a circular block, §4.8), in the plane's (a, b) coordinates with the
//! right-handed sense of [`Plane::axes`]: G2 is clockwise about the plane normal, G3
//! counter-clockwise.
//!
//! Centre forms:
//! * GOST-20999: I, J, K = centre − start, incremental whatever G90/G91 says;
//! * MC2101: the pair = start − centre with the signs ignored (written "+"): of the four sign
//!   choices the one whose end lies on the circle is taken, the shortest sweep on a tie;
//! * R: R > 0 the arc below 180°, R < 0 above; a full circle with R is error 28.
//!
//! The end must lie on the circle within the arc tolerance (machine data; [decide] §4.5: the
//! document gives no tolerance and no error number, Stanok reports `lab::arc-radius`).
//!
//! Helix (§4.5): the pitch word (K in G17, J in G18, I in G19) and the length along the normal
//! give the total angle 2π·|length|/pitch; it must equal the in-plane sweep plus whole turns
//! ([decide]: within the arc tolerance measured along the normal, else `lab::helix-pitch`). The
//! R sign rule applies to the in-plane part.

use stanok_canon::{Diagnostic, Plane, Span};
use stanok_geom::{ccw_sweep, centre_from_radius};
use std::f64::consts::TAU;

/// What a circular block gives.
pub struct ArcInput {
    /// G3.
    pub ccw: bool,
    /// Plane.
    pub plane: Plane,
    /// Start and end, machine X Y Z mm.
    pub start: [f64; 3],
    /// End.
    pub end: [f64; 3],
    /// I, J, K in mm (None when not written).
    pub ijk: [Option<f64>; 3],
    /// R in mm.
    pub radius: Option<f64>,
    /// MC2101: the centre words are start − centre, unsigned.
    pub unsigned_start_minus_centre: bool,
    /// Tolerance, mm.
    pub tol: f64,
    /// The block's span.
    pub span: Span,
}

/// The arc found: centre (machine X Y Z) and LinuxCNC turns (1 = no extra full turn).
pub struct ArcOut {
    pub centre: [f64; 3],
    pub turns: u32,
    /// In-plane path length, mm (for the feed along the arc).
    pub planar_length: f64,
}

/// The plane's centre letters' indices into I J K: (a, b), and the pitch letter.
fn letters(plane: Plane) -> (usize, usize, usize) {
    match plane {
        Plane::XY => (0, 1, 2), // I J, pitch K
        Plane::ZX => (2, 0, 1), // K I, pitch J
        Plane::YZ => (1, 2, 0), // J K, pitch I
    }
}

/// Computes the arc of a block.
pub fn arc(inp: &ArcInput) -> Result<ArcOut, Diagnostic> {
    let (a, b, n) = inp.plane.axes();
    let (la, lb, lp) = letters(inp.plane);
    let s = [inp.start[a], inp.start[b]];
    let e = [inp.end[a], inp.end[b]];
    let same = (e[0] - s[0]).hypot(e[1] - s[1]) <= 1e-9;
    let sweep_of = |c: [f64; 2]| {
        let ccw = ccw_sweep(c, s, e, 1e-9);
        if inp.ccw {
            ccw
        } else if same {
            TAU
        } else {
            TAU - ccw
        }
    };
    let centre2 = if let Some(r) = inp.radius {
        if same {
            return Err(Diagnostic::manual(
                28,
                "a full circle cannot be programmed with R",
                inp.span,
            )
            .with_note("give the centre with I, J, K"));
        }
        centre_from_radius(s, e, r.abs(), inp.ccw, r < 0.0, inp.tol).map_err(|why| {
            Diagnostic::error("lab::arc-radius", format!("arc by radius: {why}"), inp.span)
        })?
    } else {
        let (ia, ib) = (inp.ijk[la], inp.ijk[lb]);
        if ia.is_none() && ib.is_none() {
            return Err(Diagnostic::error(
                "lab::arc-centre",
                "a circular block needs its centre (I, J, K for the plane) or R",
                inp.span,
            ));
        }
        let (da, db) = (ia.unwrap_or(0.0), ib.unwrap_or(0.0));
        if inp.unsigned_start_minus_centre {
            let mut best: Option<([f64; 2], f64, f64)> = None;
            for (sa, sb) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
                let c = [s[0] - sa * da.abs(), s[1] - sb * db.abs()];
                let miss = ((e[0] - c[0]).hypot(e[1] - c[1]) - da.hypot(db)).abs();
                let sweep = sweep_of(c);
                let better = match best {
                    None => true,
                    Some((_, m, sw)) => miss + 1e-9 < m || ((miss - m).abs() <= 1e-9 && sweep < sw),
                };
                if better {
                    best = Some((c, miss, sweep));
                }
            }
            best.map(|b| b.0).unwrap_or(s)
        } else {
            [s[0] + da, s[1] + db]
        }
    };
    let r_start = (s[0] - centre2[0]).hypot(s[1] - centre2[1]);
    let r_end = (e[0] - centre2[0]).hypot(e[1] - centre2[1]);
    if (r_start - r_end).abs() > inp.tol || r_start <= 0.0 {
        return Err(Diagnostic::error(
            "lab::arc-radius",
            "the arc's end point is not on its circle",
            inp.span,
        )
        .with_note(format!(
            "radius at the start {r_start:.4} mm, at the end {r_end:.4} mm (tolerance {} mm)",
            inp.tol
        )));
    }
    let sweep = sweep_of(centre2);
    // Helix turns from the pitch.
    let mut turns = 1;
    let length = inp.end[n] - inp.start[n];
    if let Some(p) = inp.ijk[lp] {
        let p = p.abs();
        if p <= 0.0 {
            return Err(Diagnostic::error(
                "lab::helix-pitch",
                "the helix pitch must not be 0",
                inp.span,
            ));
        }
        let total = TAU * length.abs() / p;
        let extra = ((total - sweep) / TAU).round().max(0.0);
        let miss = (total - (sweep + extra * TAU)).abs() * p / TAU;
        if miss > inp.tol {
            return Err(Diagnostic::error(
                "lab::helix-pitch",
                "the helix's length and pitch do not reach its end point",
                inp.span,
            )
            .with_note(format!(
                "length {length:.3} mm / pitch {p:.3} mm = {:.4} turns; the end point needs {:.4} + whole turns",
                total / TAU,
                sweep / TAU
            )));
        }
        turns = 1 + extra as u32;
    }
    let mut centre = inp.start;
    centre[a] = centre2[0];
    centre[b] = centre2[1];
    let planar = r_start * (sweep + (turns - 1) as f64 * TAU);
    Ok(ArcOut {
        centre,
        turns,
        planar_length: planar,
    })
}
