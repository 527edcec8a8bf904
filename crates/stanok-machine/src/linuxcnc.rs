//! LinuxCNC's tool table (`.tbl`) and parameter file (`.var`): read and write, so that users can
//! bring their machine's data along (and take it back).
//!
//! ## Tool table
//!
//! One tool per line, words in any order, letters in either case, separated by blanks; `;` starts
//! the tool's comment, which runs to the end of the line. A line that starts with `;`, or is blank,
//! is skipped.
//!
//! ```text
//! T1 P1 Z-1.5 D0.25 ;tool 1
//! ```
//!
//! | word | meaning | Stanok field |
//! |---|---|---|
//! | `T` | tool number, whole, ≥ 1, once per table (required) | `Tool::number` |
//! | `P` | pocket, whole, ≥ 0 (absent = 0) | `Tool::pocket` |
//! | `X Y Z U V W` | tool offset, file units | `ToolEdge::offset` (mm) |
//! | `A B C` | tool offset, degrees | `ToolEdge::offset` |
//! | `D` | **diameter**, file units, ≥ 0 | `ToolEdge::radius` = D / 2 (mm) |
//! | `I`, `J` | front and back angle, degrees | `front_angle`, `back_angle` |
//! | `Q` | lathe orientation 0…9 | `ToolEdge::orientation` |
//!
//! A LinuxCNC tool has one edge (D1) and kind `milling`; AxiOMA's lengths L1…L3 and the wear values
//! stay 0. LinuxCNC skips a line it cannot read; Stanok refuses it (file:line:column), as it refuses
//! a word given twice, a second line for the same T, and a negative diameter (which LinuxCNC takes
//! as "compensate on the other side").
//!
//! ## Parameter file
//!
//! One parameter per line: its number, blanks, its value (`5221\t100.000000`), numbers strictly
//! increasing (LinuxCNC refuses a file out of order). Lines starting with `#` or `;` and blank lines
//! are skipped. Mapping (axis index k = 0…8 for X Y Z A B C U V W, system n = 1…9 for G54…G59.3):
//!
//! | parameters | Stanok field |
//! |---|---|
//! | 5161 + k | `OffsetTables::g28` |
//! | 5181 + k | `OffsetTables::g30` |
//! | 5210 | `g92_applied` (0 or 1) |
//! | 5211 + k | `g92` |
//! | 5220 | `active_system` (1…9) |
//! | 5201 + 20·n + k | `zero[n − 1][page 1].offset` |
//! | 5210 + 20·n | `zero[n − 1][page 1].rotation_xy`, degrees |
//! | any other 1…5601 | [`StoredOffsets::parameters`], value as written |
//!
//! Linear values are in the file's units (`units`: LinuxCNC writes the machine's units) and are
//! converted to mm; angles are degrees either way.

use crate::control::{is_offset_parameter, MAX_ORIENTATION, MAX_PARAMETER};
use crate::data::{bad_data, line_column};
use crate::StoredOffsets;
use stanok_canon::setup::{OffsetTables, Tool, ToolEdge, ToolKind, ToolTable, ZERO_OFFSET_SYSTEMS};
use stanok_canon::{Diagnostic, LengthUnits, Pose, AXIS_LETTERS};
use std::collections::BTreeMap;
use std::fmt::Write;
use std::ops::Range;

/// Is axis k (X Y Z A B C U V W order) a linear one (converted with the file's units)?
fn is_linear(k: usize) -> bool {
    !(3..=5).contains(&k)
}

/// The value of a number written in a LinuxCNC file, as f64; None unless finite.
fn read_number(text: &str) -> Option<f64> {
    text.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// The digits of a plain decimal number (`-1.5`, `.25`, `3e2`): sign, digits, power of ten.
fn decimal_parts(text: &str) -> Option<(bool, String, i64)> {
    let (negative, rest) = match text.as_bytes().first()? {
        b'-' => (true, &text[1..]),
        b'+' => (false, &text[1..]),
        _ => (false, text),
    };
    let (mantissa, exponent) = match rest.find(['e', 'E']) {
        Some(i) => (&rest[..i], rest[i + 1..].parse::<i64>().ok()?),
        None => (rest, 0),
    };
    let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let digits = format!("{int}{frac}");
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let frac_len = i64::try_from(frac.len()).ok()?;
    Some((negative, digits, exponent.checked_sub(frac_len)?))
}

/// A length written in a LinuxCNC file, in mm. An inch value is converted from its decimal text,
/// rounding once (`1.5` in → the f64 nearest 38.1, where 1.5 × 25.4 in f64 gives
/// 38.099999999999994). None unless a finite number.
fn read_length(text: &str, units: LengthUnits) -> Option<f64> {
    let v = read_number(text)?;
    if units == LengthUnits::Millimetres {
        return Some(v);
    }
    let Some((negative, digits, exponent)) = decimal_parts(text) else {
        return Some(v * units.mm_per_unit());
    };
    // digits × 254, then × 10^(exponent − 1): 25.4 = 254 / 10, exact in decimal.
    let mut product: Vec<u8> = Vec::with_capacity(digits.len() + 3);
    let mut carry = 0u32;
    for d in digits.bytes().rev() {
        let x = u32::from(d - b'0') * 254 + carry;
        product.push(b'0' + (x % 10) as u8);
        carry = x / 10;
    }
    while carry > 0 {
        product.push(b'0' + (carry % 10) as u8);
        carry /= 10;
    }
    product.reverse();
    let sign = if negative { "-" } else { "" };
    let text = format!(
        "{sign}{}e{}",
        String::from_utf8(product).ok()?,
        exponent - 1
    );
    text.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// The lines of `text` without their line ends, with the byte offset each starts at.
fn lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    let mut start = 0;
    text.split_inclusive('\n').map(move |l| {
        let at = start;
        start += l.len();
        let l = l.strip_suffix('\n').unwrap_or(l);
        (at, l.strip_suffix('\r').unwrap_or(l))
    })
}

/// The blank-separated words of `s`, each with its byte range relative to `s`.
fn words(s: &str) -> impl Iterator<Item = (Range<usize>, &str)> {
    let mut rest = s;
    let mut offset = 0;
    std::iter::from_fn(move || {
        let skip = rest.len() - rest.trim_start().len();
        offset += skip;
        rest = &rest[skip..];
        if rest.is_empty() {
            return None;
        }
        let len = rest.find(char::is_whitespace).unwrap_or(rest.len());
        let word = &rest[..len];
        let range = offset..offset + len;
        offset += len;
        rest = &rest[len..];
        Some((range, word))
    })
}

/// Writes `file_value` (a value in file units) so that reading the text back (`reads_back`) gives
/// the stored value again: LinuxCNC's own six decimals when they suffice, else the shortest text of
/// `file_value`, which is exact whenever no unit conversion is involved. `sign` writes a `+` on
/// positive numbers (`%+f`, the tool table's style).
fn exact(file_value: f64, reads_back: impl Fn(&str) -> bool, sign: bool) -> String {
    let six = if sign {
        format!("{file_value:+.6}")
    } else {
        format!("{file_value:.6}")
    };
    if reads_back(&six) {
        return six;
    }
    if sign {
        format!("{file_value:+?}")
    } else {
        format!("{file_value:?}")
    }
}

struct ToolLine {
    number: Option<(u32, Range<usize>)>,
    pocket: u32,
    edge: ToolEdge,
}

fn parse_tool_word(
    word: &str,
    at: &Range<usize>,
    units: LengthUnits,
    into: &mut ToolLine,
) -> Result<(), (String, Range<usize>)> {
    let mut chars = word.chars();
    let letter = chars.next().unwrap_or(' ').to_ascii_uppercase();
    let value = chars.as_str();
    let whole = |what: &str| {
        value.parse::<i64>().map_err(|_| {
            (
                format!("{letter} ({what}) needs a whole number, not \"{value}\""),
                at.clone(),
            )
        })
    };
    let bad = |what: &str| {
        (
            format!("{letter} ({what}) needs a number, not \"{value}\""),
            at.clone(),
        )
    };
    let number = |what: &str| read_number(value).ok_or_else(|| bad(what));
    let length = |what: &str| read_length(value, units).ok_or_else(|| bad(what));
    match letter {
        'T' => {
            let t = whole("tool number")?;
            let t = u32::try_from(t).ok().filter(|t| *t >= 1).ok_or_else(|| {
                (
                    format!("T (tool number) must be 1…{}, not {t}", u32::MAX),
                    at.clone(),
                )
            })?;
            into.number = Some((t, at.clone()));
        }
        'P' => {
            let p = whole("pocket")?;
            into.pocket = u32::try_from(p).map_err(|_| {
                (
                    format!("P (pocket) must be 0…{}, not {p}", u32::MAX),
                    at.clone(),
                )
            })?;
        }
        'D' => {
            let d = length("diameter")?;
            if d < 0.0 {
                return Err((
                    format!("D (diameter) must not be negative, not {value}"),
                    at.clone(),
                ));
            }
            into.edge.radius = d / 2.0;
        }
        'I' => into.edge.front_angle = number("front angle")?,
        'J' => into.edge.back_angle = number("back angle")?,
        'Q' => {
            let q = whole("orientation")?;
            into.edge.orientation = u8::try_from(q)
                .ok()
                .filter(|q| *q <= MAX_ORIENTATION)
                .ok_or_else(|| {
                    (
                        format!("Q (orientation) must be 0…{MAX_ORIENTATION}, not {q}"),
                        at.clone(),
                    )
                })?;
        }
        _ => {
            let Some(k) = AXIS_LETTERS.iter().position(|l| *l == letter) else {
                return Err((
                    format!(
                        "unknown word \"{word}\": a tool table line has T P X Y Z A B C U V W D I J Q"
                    ),
                    at.clone(),
                ));
            };
            let mut offset = into.edge.offset.to_array();
            offset[k] = if is_linear(k) {
                length("tool offset")?
            } else {
                number("tool offset")?
            };
            into.edge.offset = Pose::from_array(offset);
        }
    }
    Ok(())
}

/// Reads a LinuxCNC tool table. `units` is the file's length unit (the LinuxCNC machine's); the
/// table returned is in mm. `file_name` is only used in the diagnostic's note.
pub fn parse_tool_table(
    text: &str,
    file_name: &str,
    units: LengthUnits,
) -> Result<ToolTable, Diagnostic> {
    let note = format!("in LinuxCNC tool table {file_name}");
    let fail = |message: String, range: Range<usize>| bad_data(text, &note, &message, Some(range));
    let mut table = ToolTable::default();
    let mut first_line: BTreeMap<u32, u32> = BTreeMap::new();
    for (start, line) in lines(text) {
        if line.trim_start().starts_with(';') || line.trim().is_empty() {
            continue;
        }
        let (body, comment) = match line.find(';') {
            Some(i) => (&line[..i], line[i + 1..].trim()),
            None => (line, ""),
        };
        let mut parsed = ToolLine {
            number: None,
            pocket: 0,
            edge: ToolEdge::default(),
        };
        let mut seen: Vec<char> = Vec::new();
        for (range, word) in words(body) {
            let at = start + range.start..start + range.end;
            let letter = word.chars().next().unwrap_or(' ').to_ascii_uppercase();
            if seen.contains(&letter) {
                return Err(fail(
                    format!("word {letter} is given twice on this line"),
                    at,
                ));
            }
            seen.push(letter);
            parse_tool_word(word, &at, units, &mut parsed).map_err(|(m, r)| fail(m, r))?;
        }
        let body_at = start + (body.len() - body.trim_start().len());
        let Some((number, at)) = parsed.number else {
            return Err(fail(
                "a tool table line needs a T word (the tool number)".into(),
                body_at..start + body.trim_end().len(),
            ));
        };
        let line_no = line_column(text, start).0;
        if let Some(first) = first_line.insert(number, line_no) {
            return Err(fail(
                format!("tool T{number} is defined twice (first on line {first})"),
                at,
            ));
        }
        table.tools.insert(
            number,
            Tool {
                number,
                pocket: parsed.pocket,
                kind: ToolKind::Milling,
                edges: vec![parsed.edge],
                comment: comment.to_string(),
                // A `.tbl` line holds no body: the simulation's defaults from D apply.
                body: Default::default(),
            },
        );
    }
    Ok(table)
}

/// Writes a tool table the way LinuxCNC does (`T1   P1   D+0.250000 Z-1.500000 ;tool 1`: T and P
/// always, the other words only when not zero), in file units `units`. Only what a LinuxCNC table
/// holds is written: edge D1's offset, diameter, angles and orientation, and the comment (line
/// breaks become blanks). AxiOMA lengths, wear, the kind and edges D2…D4 are left out; a tool
/// without edges is written as T and P only.
pub fn write_tool_table(table: &ToolTable, units: LengthUnits) -> String {
    let scale = units.mm_per_unit();
    let mut out = String::new();
    for tool in table.tools.values() {
        let e = tool.edges.first().copied().unwrap_or_default();
        let _ = write!(out, "T{:<3} P{:<3}", tool.number, tool.pocket);
        if e.radius != 0.0 {
            let back = |t: &str| read_length(t, units).map(|d| d / 2.0) == Some(e.radius);
            let _ = write!(out, " D{}", exact(e.radius * 2.0 / scale, back, true));
        }
        for (k, v) in e.offset.to_array().into_iter().enumerate() {
            if v != 0.0 {
                let text = if is_linear(k) {
                    exact(v / scale, |t| read_length(t, units) == Some(v), true)
                } else {
                    exact(v, |t| read_number(t) == Some(v), true)
                };
                let _ = write!(out, " {}{text}", AXIS_LETTERS[k]);
            }
        }
        for (letter, v) in [('I', e.front_angle), ('J', e.back_angle)] {
            if v != 0.0 {
                let text = exact(v, |t| read_number(t) == Some(v), true);
                let _ = write!(out, " {letter}{text}");
            }
        }
        if e.orientation != 0 {
            let _ = write!(out, " Q{}", e.orientation);
        }
        let comment: String = tool
            .comment
            .chars()
            .map(|c| if c == '\n' || c == '\r' { ' ' } else { c })
            .collect();
        let comment = comment.trim();
        if !comment.is_empty() {
            let _ = write!(out, " ;{comment}");
        }
        out.push('\n');
    }
    out
}

/// The first parameter of zero-offset system n (1 = G54 … 9 = G59.3): 5201 + 20·n.
fn system_base(n: usize) -> u32 {
    5201 + 20 * n as u32
}

/// Stores parameter `n`, written as `text`, into `into`; `Err` says why the value is refused.
fn apply_parameter(
    n: u32,
    text: &str,
    units: LengthUnits,
    into: &mut StoredOffsets,
) -> Result<(), String> {
    let v = read_number(text)
        .ok_or_else(|| format!("parameter {n} needs a finite number, not \"{text}\""))?;
    let o = &mut into.offsets;
    let set = |pose: &mut Pose, k: usize| {
        let mut a = pose.to_array();
        // read_length succeeds wherever read_number does.
        a[k] = if is_linear(k) {
            read_length(text, units).unwrap_or(v)
        } else {
            v
        };
        *pose = Pose::from_array(a);
    };
    let axis = |base: u32| (n - base) as usize;
    match n {
        5161..=5169 => set(&mut o.g28, axis(5161)),
        5181..=5189 => set(&mut o.g30, axis(5181)),
        5211..=5219 => set(&mut o.g92, axis(5211)),
        5210 => {
            o.g92_applied = match v {
                0.0 => false,
                1.0 => true,
                _ => return Err(format!("5210 (G92 applied) must be 0 or 1, not {v}")),
            }
        }
        5220 => {
            if v.fract() != 0.0 || !(1.0..=ZERO_OFFSET_SYSTEMS as f64).contains(&v) {
                return Err(format!(
                    "5220 (active coordinate system) must be 1…{ZERO_OFFSET_SYSTEMS}, not {v}"
                ));
            }
            o.active_system = v as u8;
        }
        _ if is_offset_parameter(n) => {
            let s = (n - 5221) as usize / 20;
            let k = (n - 5221) as usize % 20;
            let z = &mut o.zero[s][0];
            if k == 9 {
                z.rotation_xy = v;
            } else {
                set(&mut z.offset, k);
            }
        }
        _ => {
            into.parameters.insert(n, v);
        }
    }
    Ok(())
}

/// Reads a LinuxCNC parameter file (`.var`). Linear offsets are in `units` (the LinuxCNC machine's)
/// and come back in mm; parameters that are not offsets are kept as written. `file_name` is only
/// used in the diagnostic's note.
pub fn parse_var_file(
    text: &str,
    file_name: &str,
    units: LengthUnits,
) -> Result<StoredOffsets, Diagnostic> {
    let note = format!("in LinuxCNC parameter file {file_name}");
    let fail = |message: String, range: Range<usize>| bad_data(text, &note, &message, Some(range));
    let mut out = StoredOffsets::default();
    let mut previous: Option<(u32, u32)> = None;
    for (start, line) in lines(text) {
        let trimmed = line.trim_start();
        if trimmed.is_empty() || trimmed.starts_with('#') || trimmed.starts_with(';') {
            continue;
        }
        let fields: Vec<(Range<usize>, &str)> = words(line)
            .map(|(r, w)| (start + r.start..start + r.end, w))
            .collect();
        let [(n_at, n_text), (v_at, v_text)] = fields.as_slice() else {
            let whole = start..start + line.len();
            let at = fields.get(2).map_or(whole, |(r, _)| r.clone());
            return Err(fail(
                "a parameter line is a number and a value (e.g. \"5221\t100.000000\")".into(),
                at,
            ));
        };
        let n = n_text
            .parse::<u32>()
            .ok()
            .filter(|n| (1..=MAX_PARAMETER).contains(n))
            .ok_or_else(|| {
                fail(
                    format!("parameter number must be 1…{MAX_PARAMETER}, not \"{n_text}\""),
                    n_at.clone(),
                )
            })?;
        let line_no = line_column(text, start).0;
        if let Some((p, p_line)) = previous {
            if n <= p {
                return Err(fail(
                    format!(
                        "parameter {n} comes after {p} (line {p_line}): LinuxCNC needs increasing numbers"
                    ),
                    n_at.clone(),
                ));
            }
        }
        previous = Some((n, line_no));
        apply_parameter(n, v_text, units, &mut out).map_err(|m| fail(m, v_at.clone()))?;
    }
    Ok(out)
}

/// The parameters LinuxCNC keeps in its file (its `_required_parameters`), taken from
/// `data.offsets`, plus `data.parameters` (an entry that is an offset's number is ignored: the
/// offset wins). Each as number → (stored value in mm/deg, value in file units, is a length).
fn var_values(data: &StoredOffsets, scale: f64) -> BTreeMap<u32, (f64, f64, bool)> {
    // number → (mm or deg value, file value, linear)
    let mut all = BTreeMap::new();
    let o: &OffsetTables = &data.offsets;
    for (n, v) in &data.parameters {
        if !is_offset_parameter(*n) {
            all.insert(*n, (*v, *v, false));
        }
    }
    let mut pose = |base: u32, p: &Pose| {
        for (k, v) in p.to_array().into_iter().enumerate() {
            let file = if is_linear(k) { v / scale } else { v };
            all.insert(base + k as u32, (v, file, is_linear(k)));
        }
    };
    pose(5161, &o.g28);
    pose(5181, &o.g30);
    pose(5211, &o.g92);
    for s in 0..ZERO_OFFSET_SYSTEMS {
        let z = o
            .zero
            .get(s)
            .and_then(|pages| pages.first())
            .copied()
            .unwrap_or_default();
        pose(system_base(s + 1), &z.offset);
    }
    for s in 0..ZERO_OFFSET_SYSTEMS {
        let z = o
            .zero
            .get(s)
            .and_then(|pages| pages.first())
            .copied()
            .unwrap_or_default();
        all.insert(
            system_base(s + 1) + 9,
            (z.rotation_xy, z.rotation_xy, false),
        );
    }
    let applied = f64::from(u8::from(o.g92_applied));
    all.insert(5210, (applied, applied, false));
    let active = f64::from(o.active_system);
    all.insert(5220, (active, active, false));
    all
}

/// Writes a LinuxCNC parameter file: every parameter LinuxCNC keeps (G28, G30, G92, the active
/// system, G54…G59.3 page 1 with rotation) and the other parameters, sorted, one `number\tvalue` a
/// line, values in file units `units` with LinuxCNC's six decimals when they are exact (else the
/// shortest exact text). Pages 2…32, workpiece frames and home positions have no LinuxCNC
/// parameters and are not written.
pub fn write_var_file(data: &StoredOffsets, units: LengthUnits) -> String {
    let scale = units.mm_per_unit();
    let mut out = String::new();
    for (n, (value, file, linear)) in var_values(data, scale) {
        let text = if linear {
            exact(file, |t| read_length(t, units) == Some(value), false)
        } else {
            exact(file, |t| read_number(t) == Some(value), false)
        };
        let _ = writeln!(out, "{n}\t{text}");
    }
    out
}

#[cfg(test)]
#[path = "linuxcnc_tests.rs"]
mod tests;
