//! The calculation, step by step (the order of spec §5.6). Each helper returns the numbers it
//! found and pushes onto its `Step` the cells it read and the working it did, so the trace is
//! built by the same code that computes, and cannot drift from it.
//!
//! Decisions where the spec leaves a choice ([decide], taken as the spec proposes):
//! * a feed range of table 2.4 gives its lower bound (the spec's worked examples do) unless the
//!   user gives `feed_mm_rev`;
//! * machine feed: the largest available feed ≤ the wanted one; machine speed: the largest
//!   available speed ≤ n (the text says "<"; the spec proposes allowing "≤");
//! * table 2.6 boundary S = 0.3 (steel) / 0.4 (iron) belongs to the first row ("S ≤ 0.3");
//! * K_nv range: the user's value inside it, else the lower bound;
//! * tool life T: 60 min for turning (upper end of 30–60), 120 min for form and thread cutters;
//! * band edges of table 2.4 (diameter, depth): a value on an edge belongs to the lower band
//!   ("up to 20" includes 20).

use crate::tables::{CvRow, Tables};
use crate::{
    Calculation, CuttingError, DepthInput, Operation, PassKind, PassResult, Step, TurningInput,
    WorkMaterial,
};
use std::f64::consts::PI;

/// Spindle speed n = 1000·v/(π·D), rpm, for a cutting speed v (m/min) on a diameter D (mm).
pub fn spindle_speed_rpm(v_m_min: f64, diameter_mm: f64) -> f64 {
    1000.0 * v_m_min / (PI * diameter_mm)
}

/// Cutting speed v = π·D·n/1000, m/min, of a spindle speed n (rpm) on a diameter D (mm).
pub fn cutting_speed_m_min(diameter_mm: f64, n_rpm: f64) -> f64 {
    PI * diameter_mm * n_rpm / 1000.0
}

/// Runs the lab's method on `input` with `tables` (normally [`Tables::lab`]).
pub fn calculate(tables: &Tables, input: &TurningInput) -> Result<Calculation, CuttingError> {
    validate(input)?;
    let grade = tables
        .grade(&input.tool)
        .ok_or_else(|| CuttingError::UnknownTool(input.tool.clone()))?;
    let carbide = grade.class == "carbide";
    let tool = tool_step(tables, input, &grade.name, carbide);
    let mut passes = Vec::new();
    let mut diameter = input.diameter_mm;
    for (i, (kind, t)) in plan_passes(&input.depth).into_iter().enumerate() {
        let pass = one_pass(tables, input, &grade.name, carbide, i, kind, t, diameter)?;
        // The next pass turns the diameter this one leaves (external turning: D − 2t).
        diameter -= 2.0 * t;
        passes.push(pass);
    }
    Ok(Calculation {
        source: tables.source.clone(),
        input: input.clone(),
        tool,
        passes,
        not_in_document: vec![
            "spindle power check, cutting force and torque: the document asks about the power \
             check (review question 7) but gives no formula"
                .into(),
            "machining (cycle) time: not covered by the document".into(),
            "Cv for malleable cast iron and for high-speed-steel tools: table 2.6 has none".into(),
        ],
    })
}

fn validate(input: &TurningInput) -> Result<(), CuttingError> {
    let positive = |v: f64, what: &str| {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(CuttingError::BadInput(format!(
                "{what} must be a positive number, not {v}"
            )))
        }
    };
    positive(input.diameter_mm, "the diameter")?;
    match &input.depth {
        DepthInput::Pass { t_mm, .. } => positive(*t_mm, "the depth of cut")?,
        DepthInput::Allowance {
            allowance_mm,
            split,
        } => {
            positive(*allowance_mm, "the allowance")?;
            for s in split {
                positive(*s, "every share of --split")?;
            }
            let sum: f64 = split.iter().sum();
            if split.is_empty() || (sum - 1.0).abs() > 1e-6 {
                return Err(CuttingError::BadInput(format!(
                    "the shares of --split must add up to 1, not {sum:.4}"
                )));
            }
            if 2.0 * allowance_mm >= input.diameter_mm {
                return Err(CuttingError::BadInput(
                    "the allowance takes the whole diameter".into(),
                ));
            }
        }
    }
    if let Some(s) = input.material.sigma_b() {
        positive(s, "σ_B")?;
    }
    if let Some(h) = input.material.hb() {
        positive(h, "HB")?;
    }
    for (v, what) in [
        (input.feed_mm_rev, "the feed"),
        (input.finish_feed_mm_rev, "the finish feed"),
        (input.nose_radius_mm, "the nose radius"),
        (input.tool_life_min, "the tool life"),
        (input.centre_height_mm, "the centre height"),
        (input.surface_factor, "K_nv"),
    ] {
        if let Some(v) = v {
            positive(v, what)?;
        }
    }
    for &f in &input.machine_feeds {
        positive(f, "every machine feed")?;
    }
    for &n in &input.machine_speeds {
        positive(n, "every machine speed")?;
    }
    Ok(())
}

/// The passes: kind and depth.
fn plan_passes(depth: &DepthInput) -> Vec<(PassKind, f64)> {
    match depth {
        DepthInput::Pass { t_mm, pass } => vec![(*pass, *t_mm)],
        DepthInput::Allowance {
            allowance_mm,
            split,
        } => split
            .iter()
            .enumerate()
            .map(|(i, share)| {
                let kind = if i == 0 {
                    PassKind::Rough
                } else {
                    PassKind::Finish
                };
                (kind, allowance_mm * share)
            })
            .collect(),
    }
}

/// Step 0: the grade against table 2.2, and the holder from the centre height (table 2.3).
fn tool_step(tables: &Tables, input: &TurningInput, grade: &str, carbide: bool) -> Step {
    let mut step = Step::new("tool material and holder (table 2.2, §5.2, table 2.3)");
    // Table 2.2 has columns for cast iron HB 240 and HB 400-700; a hardness between them goes to
    // the nearer one (threshold 320, our choice: the document gives no rule).
    let (column, column_name) = match input.material {
        WorkMaterial::GreyIron { hb } | WorkMaterial::MalleableIron { hb } if hb > 320.0 => {
            ("cast_iron_hb400_700", "cast iron HB 400-700")
        }
        WorkMaterial::GreyIron { .. } | WorkMaterial::MalleableIron { .. } => {
            ("cast_iron_hb240", "cast iron HB 240")
        }
        _ => ("steel", "carbon and alloy steel"),
    };
    let mut recommended = false;
    for row in &tables.tool_material {
        let grades = match column {
            "steel" => &row.steel,
            "cast_iron_hb240" => &row.cast_iron_hb240,
            _ => &row.cast_iron_hb400_700,
        };
        let listed = if grades.is_empty() {
            "-".to_string()
        } else {
            grades.join(", ")
        };
        step.lines
            .push(format!("table 2.2, {column_name}, {}: {listed}", row.work));
        if grades.iter().any(|g| {
            g.split([' ', '(', ')', '?'])
                .any(|w| w.eq_ignore_ascii_case(grade))
        }) {
            recommended = true;
        }
    }
    let class = if carbide {
        "carbide"
    } else {
        "high-speed steel"
    };
    step.lines.push(if recommended {
        format!("chosen: {grade} ({class}), recommended by table 2.2 for this material")
    } else {
        format!(
            "chosen: {grade} ({class}), NOT among table 2.2's recommendations for this material"
        )
    });
    match input.centre_height_mm {
        None => step
            .defaults
            .push("no --centre-height: holder section not chosen".into()),
        Some(h) => match tables
            .holder
            .iter()
            .find(|r| h >= r.centre_height[0] && h <= r.centre_height[1])
        {
            None => step.lines.push(format!(
                "centre height {h} mm: the document gives sections for 150-160, 180-200 and 250-300 mm only"
            )),
            Some(r) => {
                step.lines.push(format!(
                    "centre height {h} mm (band {}-{} mm): holder section B x H = {}",
                    r.centre_height[0],
                    r.centre_height[1],
                    r.sections.join(" to ")
                ));
                for s in &r.sections {
                    let (b, hh) = s.split_once('x').unwrap_or(("0", "0"));
                    let (b, hh): (f64, f64) = (b.parse().unwrap_or(0.0), hh.parse().unwrap_or(0.0));
                    for c in tables.cutter.iter().filter(|c| c.b == b && c.h == hh) {
                        step.lines.push(format!(
                            "table 2.3: bent through cutter {} (H x B = {} x {}, length {}, insert {})",
                            c.designation, c.h, c.b, c.length, c.insert
                        ));
                    }
                }
            }
        },
    }
    step
}

#[allow(clippy::too_many_arguments)]
fn one_pass(
    tables: &Tables,
    input: &TurningInput,
    grade: &str,
    carbide: bool,
    index: usize,
    kind: PassKind,
    t: f64,
    diameter: f64,
) -> Result<PassResult, CuttingError> {
    if diameter <= 0.0 {
        return Err(CuttingError::BadInput(
            "the passes take the whole diameter".into(),
        ));
    }
    let mut depth_step = Step::new("depth of cut (§5.3)");
    match &input.depth {
        DepthInput::Pass { .. } => depth_step.lines.push(format!("t = {t:.3} mm (given)")),
        DepthInput::Allowance {
            allowance_mm,
            split,
        } => depth_step.lines.push(format!(
            "t = allowance × share = {allowance_mm} × {} = {t:.3} mm",
            split[index]
        )),
    }
    depth_step
        .lines
        .push(format!("D = {diameter:.3} mm (work diameter of this pass)"));
    if kind == PassKind::Finish && !(0.1..=2.0).contains(&t) {
        depth_step.lines.push(format!(
            "note: finishing depth {t:.3} mm is outside the document's 0.5-2 mm (Rz ≤ 20) and 0.1-0.4 mm (finer)"
        ));
    }

    let (feed_step, range, wanted, feed) = feed(tables, input, index, kind, t, diameter)?;
    let (cv_step, row) = cv_row(tables, input, feed)?;
    let (kv_step, k_mv, k_nv, k_uv) = kv(tables, input, grade, carbide, index)?;
    let k_v = k_mv * k_nv * k_uv;

    // Step: the speed. Formula 1: v = Cv/(T^m·t^x·S^y)·Kv; formula 2 drops t^x.
    let mut v_step = Step::new("cutting speed and spindle speed (§5.5)");
    let default_life = if matches!(input.operation, Operation::FormTurning) {
        120.0
    } else {
        60.0
    };
    let life = input.tool_life_min.unwrap_or(default_life);
    if input.tool_life_min.is_none() {
        v_step.defaults.push(format!(
            "tool life T = {default_life} min (default: 60 for turning cutters, the upper end of the document's 30-60; 120 for form cutters)"
        ));
    }
    let y = row.y.unwrap_or(0.0);
    let t_pow_m = life.powf(row.m);
    let s_pow_y = feed.powf(y);
    let t_pow_x = (row.formula == 1).then(|| t.powf(row.x.unwrap_or(0.0)));
    let product = t_pow_m * t_pow_x.unwrap_or(1.0) * s_pow_y;
    let v = row.cv / product * k_v;
    v_step
        .lines
        .push(format!("T^m = {life}^{} = {t_pow_m:.4}", row.m));
    if let Some(tx) = t_pow_x {
        v_step
            .lines
            .push(format!("t^x = {t:.3}^{} = {tx:.4}", row.x.unwrap_or(0.0)));
    }
    v_step
        .lines
        .push(format!("S^y = {feed}^{y} = {s_pow_y:.4}"));
    if row.formula == 1 {
        v_step.lines.push(format!(
            "v = Cv / (T^m · t^x · S^y) · Kv = {} / {product:.4} × {k_v:.4} = {v:.2} m/min",
            row.cv
        ));
    } else {
        v_step.lines.push(format!(
            "v = Cv / (T^m · S^y) · Kv (formula 2) = {} / {product:.4} × {k_v:.4} = {v:.2} m/min",
            row.cv
        ));
    }
    let n = spindle_speed_rpm(v, diameter);
    v_step.lines.push(format!(
        "n = 1000 · v / (π · D) = 1000 × {v:.2} / (π × {diameter:.3}) = {n:.1} rpm"
    ));
    let (n_act, v_act) = if input.machine_speeds.is_empty() {
        v_step
            .defaults
            .push("no --machine-speeds: n is not corrected to the machine".into());
        (None, None)
    } else {
        let n_act = nearest_at_or_below(&input.machine_speeds, n)
            .ok_or(CuttingError::NoLowerMachineSpeed(n))?;
        let v_act = cutting_speed_m_min(diameter, n_act);
        v_step.lines.push(format!(
            "n_act = {n_act} rpm (the largest machine speed ≤ n)"
        ));
        v_step
            .defaults
            .push("machine speed n_act ≤ n (the method's text says \"<\"; an equal speed is allowed here)".into());
        v_step.lines.push(format!(
            "v_act = π · D · n_act / 1000 = π × {diameter:.3} × {n_act} / 1000 = {v_act:.2} m/min"
        ));
        (Some(n_act), Some(v_act))
    };

    Ok(PassResult {
        number: index + 1,
        kind,
        depth_mm: t,
        diameter_mm: diameter,
        feed_table_range_mm_rev: range,
        feed_wanted_mm_rev: wanted,
        feed_mm_rev: feed,
        formula: row.formula,
        cv: row.cv,
        x: if row.formula == 1 { row.x } else { None },
        y,
        m: row.m,
        tool_life_min: life,
        k_mv,
        k_nv,
        k_uv,
        k_v,
        t_pow_m,
        t_pow_x,
        s_pow_y,
        v_m_min: v,
        n_rpm: n,
        n_act_rpm: n_act,
        v_act_m_min: v_act,
        steps: vec![depth_step, feed_step, kv_step, cv_step, v_step],
    })
}

/// The largest value of `list` that is ≤ `limit` (a relative 1e-9 slack so that a value printed
/// equal to the limit counts as equal).
fn nearest_at_or_below(list: &[f64], limit: f64) -> Option<f64> {
    list.iter()
        .copied()
        .filter(|&v| v <= limit * (1.0 + 1e-9))
        .fold(None, |best: Option<f64>, v| {
            Some(best.map_or(v, |b| b.max(v)))
        })
}

/// Step 2: the feed. Returns (step, table range, wanted feed, feed after the machine correction).
#[allow(clippy::type_complexity)]
fn feed(
    tables: &Tables,
    input: &TurningInput,
    index: usize,
    kind: PassKind,
    t: f64,
    diameter: f64,
) -> Result<(Step, Option<[f64; 2]>, f64, f64), CuttingError> {
    let mut step = Step::new("feed (tables 2.4, 2.5, corrected to the machine)");
    let given = if index == 0 {
        input.feed_mm_rev
    } else {
        input.finish_feed_mm_rev
    };
    let mut range = None;
    let wanted = if let Some(s) = given {
        step.lines.push(format!("S = {s} mm/rev (given)"));
        s
    } else if kind == PassKind::Rough {
        if matches!(
            input.operation,
            Operation::PartingOff
                | Operation::Grooving
                | Operation::FormTurning
                | Operation::Threading
        ) {
            return Err(CuttingError::FeedOutsideTable(
                "table 2.4 gives feeds for external turning only: give --feed for this operation"
                    .into(),
            ));
        }
        let group = if input.material.is_steel() {
            "steel"
        } else {
            "cast_iron"
        };
        let row = tables
            .rough_feed
            .rows
            .iter()
            .find(|r| {
                r.group == group
                    && diameter > r.d[0]
                    && diameter <= r.d[1]
                    && t > r.t[0]
                    && t <= r.t[1]
            })
            .ok_or_else(|| {
                CuttingError::FeedOutsideTable(format!(
                    "table 2.4 has no feed for {group}, D = {diameter:.3} mm, t = {t:.3} mm (it covers D ≤ 600 mm, t ≤ 8 mm, and some cells are empty): give --feed"
                ))
            })?;
        let row_name = format!("D {}-{} mm", r0(row.d[0]), r0(row.d[1]));
        let col = format!(
            "{}, t {}-{} mm",
            if group == "steel" {
                "steel"
            } else {
                "cast iron and copper alloys"
            },
            r0(row.t[0]),
            r0(row.t[1])
        );
        step.cell("2.4", &row_name, &col, row.s[0], row.doubt.as_deref());
        step.cell("2.4", &row_name, &col, row.s[1], row.doubt.as_deref());
        step.lines.push(format!(
            "table 2.4: S = {}-{} mm/rev; S = {} mm/rev (the lower bound)",
            row.s[0], row.s[1], row.s[0]
        ));
        step.defaults
            .push("a table feed range gives its lower bound (--feed chooses another)".into());
        if input.operation != Operation::Longitudinal {
            step.lines.push(
                "note: table 2.4 is for external longitudinal turning; used here as the nearest data"
                    .into(),
            );
        }
        range = Some(row.s);
        row.s[0]
    } else {
        let (Some(rough), Some(r)) = (&input.roughness, input.nose_radius_mm) else {
            return Err(CuttingError::FeedOutsideTable(
                "a finish pass takes its feed from table 2.5: give --roughness and --nose-radius (or the feed)"
                    .into(),
            ));
        };
        let table = &tables.finish_feed;
        let row = table
            .rows
            .iter()
            .find(|row| row.roughness.eq_ignore_ascii_case(rough))
            .ok_or_else(|| {
                CuttingError::FeedOutsideTable(format!(
                    "table 2.5 has no row {rough} (rows: Ra2.5, Rz20, Rz40, Rz80)"
                ))
            })?;
        let col = table
            .nose_radius
            .iter()
            .position(|&c| (c - r).abs() < 1e-9)
            .ok_or_else(|| {
                CuttingError::FeedOutsideTable(format!(
                    "table 2.5 has no column r = {r} mm (columns 0.4, 0.8, 1.2, 1.6, 2.0, 2.4)"
                ))
            })?;
        let s = row.s[col];
        step.cell("2.5", &row.roughness, &format!("r = {r} mm"), s, None);
        step.lines.push(format!(
            "table 2.5: {}, r = {r} mm: S = {s} mm/rev",
            row.roughness
        ));
        s
    };
    let feed = if input.machine_feeds.is_empty() {
        step.defaults
            .push("no --machine-feeds: the feed is not corrected to the machine".into());
        wanted
    } else {
        let f = nearest_at_or_below(&input.machine_feeds, wanted)
            .ok_or(CuttingError::NoLowerMachineFeed(wanted))?;
        step.lines.push(format!(
            "machine feed: S = {f} mm/rev (the nearest available ≤ {wanted})"
        ));
        f
    };
    Ok((step, range, wanted, feed))
}

/// A band edge as printed ("0" for the open lower end).
fn r0(v: f64) -> String {
    format!("{v}")
}

/// Step 3: the row of table 2.6.
fn cv_row<'t>(
    tables: &'t Tables,
    input: &TurningInput,
    feed: f64,
) -> Result<(Step, &'t CvRow), CuttingError> {
    let mut step = Step::new("Cv, x, y, m (table 2.6)");
    let group =
        match input.material {
            WorkMaterial::GreyIron { .. } => "grey_iron",
            WorkMaterial::MalleableIron { .. } => return Err(CuttingError::NoCvRow(
                "the document has no Cv row for malleable cast iron (table 2.7 gives its K_mv, \
                 table 2.6 no Cv); the lab's own malleable-iron part cannot be computed from the \
                 document's data alone"
                    .into(),
            )),
            _ => "steel",
        };
    let operation = input.operation.cv_operation();
    if input.operation == Operation::Threading && group != "grey_iron" {
        return Err(CuttingError::NoFormulaForThreading(
            "the document gives thread-cutting coefficients only for grey cast iron (table 2.6), \
             and no formula for thread cutting at all"
                .into(),
        ));
    }
    let row = tables
        .cv
        .iter()
        .find(|r| {
            r.group == group
                && r.operation == operation
                && !r.feed_max.is_some_and(|max| feed > max)
                && !r.feed_over.is_some_and(|over| feed <= over)
        })
        .ok_or_else(|| {
            CuttingError::NoCvRow(format!("no row for {group}, {operation}, S = {feed}"))
        })?;
    if row.formula == 0 {
        return Err(CuttingError::NoFormulaForThreading(format!(
            "table 2.6 gives Cv = {}, x = {}, m = {} for thread cutting ({}), but the document gives no formula for it",
            row.cv,
            row.x.unwrap_or(0.0),
            row.m,
            row.tool
        )));
    }
    if input.tool_is_hss_for(tables) {
        return Err(CuttingError::NoCvRow(format!(
            "table 2.6 has carbide rows only; {} is a high-speed-steel tool",
            input.tool
        )));
    }
    let band = match (row.feed_max, row.feed_over) {
        (Some(m), _) => format!("S ≤ {m}"),
        (_, Some(o)) => format!("S > {o}"),
        _ => "any S".into(),
    };
    let row_name = format!("{}, {}, {}, {band}", row.reference, row.operation, row.tool);
    let note = |c: &str| {
        if row.merged.iter().any(|m| m == c) {
            row.doubt.as_deref()
        } else {
            None
        }
    };
    step.cell("2.6", &row_name, "Cv", row.cv, None);
    if row.formula == 1 {
        step.cell("2.6", &row_name, "x", row.x.unwrap_or(0.0), note("x"));
    }
    step.cell("2.6", &row_name, "y", row.y.unwrap_or(0.0), None);
    step.cell("2.6", &row_name, "m", row.m, note("m"));
    if row.merged.iter().any(|m| m == "feed") {
        step.lines.push(format!(
            "note: {}",
            row.doubt.as_deref().unwrap_or("merged cell")
        ));
    }
    step.lines.push(format!(
        "row for S = {feed} mm/rev: Cv = {}, {}y = {}, m = {} (formula {})",
        row.cv,
        if row.formula == 1 {
            format!("x = {}, ", row.x.unwrap_or(0.0))
        } else {
            String::new()
        },
        row.y.unwrap_or(0.0),
        row.m,
        row.formula
    ));
    if matches!(row.feed_max, Some(m) if (feed - m).abs() < 1e-12) {
        step.defaults.push(format!(
            "S = {feed} on the boundary of two rows: the first row (\"S ≤ {feed}\", as handbooks read it)"
        ));
    }
    if operation == "parting" && input.operation != Operation::PartingOff {
        step.lines.push(
            "note: table 2.6 gives parting-off coefficients; used for grooving and form turning (same formula 2)"
                .into(),
        );
    }
    Ok((step, row))
}

impl TurningInput {
    fn tool_is_hss_for(&self, tables: &Tables) -> bool {
        tables.grade(&self.tool).is_some_and(|g| g.class == "hss")
    }
}

/// Step 4: K_mv, K_nv, K_uv.
fn kv(
    tables: &Tables,
    input: &TurningInput,
    grade: &str,
    carbide: bool,
    index: usize,
) -> Result<(Step, f64, f64, f64), CuttingError> {
    let mut step =
        Step::new("correction factor Kv = K_mv · K_nv · K_uv (tables 2.7, 2.8, K_nv, 2.9)");
    let key = input.material.kmv_key();
    let sigma = input.material.sigma_b();
    let row = tables
        .kmv
        .iter()
        .find(|r| {
            r.material == key
                && match (r.sigma_b, sigma) {
                    (Some(band), Some(s)) => s > band[0] && s <= band[1],
                    _ => true,
                }
        })
        .ok_or_else(|| CuttingError::BadInput(format!("table 2.8 has no row for {key}")))?;
    let tool_col = if carbide { "carbide" } else { "HSS" };
    let merged_nv = carbide && row.merged.iter().any(|m| m == "nv_carbide");
    let nv = if carbide { row.nv_carbide } else { row.nv_hss };
    let nv_column = if carbide { "nv_carbide" } else { "nv_hss" };
    let nv_note = if merged_nv {
        Some("blank as printed: the 1.0 printed in the Cr-Ni row read as applying to all steels (merged cell)")
    } else if row.doubt_column.as_deref() == Some(nv_column) {
        row.doubt.as_deref()
    } else {
        None
    };
    let k_mv = if let Some(s) = sigma {
        let kr = if carbide { row.kr_carbide } else { row.kr_hss }.unwrap_or(1.0);
        step.cell("2.8", &row.row, &format!("K_r, {tool_col}"), kr, None);
        step.cell("2.8", &row.row, &format!("n_v, {tool_col}"), nv, nv_note);
        let k = kr * (750.0 / s).powf(nv);
        step.lines.push(format!(
            "K_mv = K_r · (750 / σ_B)^n_v = {kr} × (750 / {s})^{nv} = {k:.4}"
        ));
        k
    } else {
        let hb = input.material.hb().unwrap_or(190.0);
        let base = if key == "grey_iron" { 190.0 } else { 150.0 };
        step.cell("2.8", &row.row, &format!("n_v, {tool_col}"), nv, nv_note);
        let k = (base / hb).powf(nv);
        step.lines.push(format!(
            "K_mv = ({base} / HB)^n_v = ({base} / {hb})^{nv} = {k:.4}"
        ));
        k
    };

    // K_nv: the blank's skin is on the first pass only.
    let k_nv = if index > 0 {
        step.lines
            .push("K_nv = 1.0 (the first pass removed the scale)".into());
        1.0
    } else {
        let row = tables
            .knv
            .iter()
            .find(|r| r.surface.eq_ignore_ascii_case(&input.surface))
            .ok_or_else(|| CuttingError::UnknownSurface(input.surface.clone()))?;
        let k = match input.surface_factor {
            Some(k) if k >= row.k[0] - 1e-12 && k <= row.k[1] + 1e-12 => k,
            Some(k) => {
                return Err(CuttingError::BadInput(format!(
                    "K_nv = {k} is outside the document's {}-{} for {}",
                    row.k[0], row.k[1], row.row
                )))
            }
            None => {
                if row.k[0] != row.k[1] {
                    step.defaults.push(format!(
                        "K_nv range {}-{}: the lower bound (--surface-factor gives another)",
                        row.k[0], row.k[1]
                    ));
                }
                row.k[0]
            }
        };
        step.cell("K_nv", &row.row, "K_nv", k, None);
        step.lines.push(format!("K_nv = {k} ({})", row.row));
        k
    };

    let group = if input.material.is_steel() {
        "structural_steel"
    } else {
        "cast_iron"
    };
    let found = tables
        .kuv
        .rows
        .iter()
        .find(|r| r.group == group && r.tool.eq_ignore_ascii_case(grade))
        .or_else(|| {
            tables
                .kuv
                .rows
                .iter()
                .find(|r| r.group == "general" && r.tool.eq_ignore_ascii_case(grade))
        })
        .ok_or_else(|| CuttingError::NoKuvEntry {
            tool: grade.to_string(),
            group: group.replace('_', " "),
        })?;
    let group_name = match found.group.as_str() {
        "structural_steel" => "structural steel",
        "cast_iron" => "grey and malleable cast iron",
        _ => "steel, cast iron, copper and aluminium alloys",
    };
    step.cell("2.9", group_name, grade, found.k, found.doubt.as_deref());
    step.lines
        .push(format!("K_uv = {} ({grade} on {group_name})", found.k));
    let k_v = k_mv * k_nv * found.k;
    step.lines
        .push(format!("Kv = {k_mv:.4} × {k_nv} × {} = {k_v:.4}", found.k));
    Ok((step, k_mv, k_nv, found.k))
}
