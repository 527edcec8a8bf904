//! Hints the command line adds to diagnostics, from what only it knows: the machine chosen and the
//! built-in machines there are. (The interpreter knows neither: it is told which axes exist.)

use stanok_canon::Diagnostic;
use stanok_machine::{MachineData, BUILTIN_MACHINES};

/// The axis letter of an "axis is not configured" diagnostic.
fn missing_axis(d: &Diagnostic) -> Option<char> {
    if d.code.to_string() != "interp::axis-not-configured" {
        return None;
    }
    let at = d.message.find(" axis is not configured")?;
    d.message[..at]
        .chars()
        .last()
        .filter(|c| c.is_ascii_uppercase())
}

/// The built-in machines that have axis `letter`.
pub fn machines_with_axis(letter: char) -> Vec<&'static str> {
    BUILTIN_MACHINES
        .iter()
        .copied()
        .filter(|name| {
            MachineData::builtin(name).is_some_and(|m| m.axes.iter().any(|a| a.name == letter))
        })
        .collect()
}

/// Adds what the user can do about `d` on `machine`.
pub fn enrich(d: &mut Diagnostic, machine: &MachineData) {
    if let Some(letter) = missing_axis(d) {
        let axes: String = machine.axes.iter().map(|a| a.name).collect();
        let with = machines_with_axis(letter);
        let note = if with.is_empty() {
            format!(
                "machine `{}` has the axes {axes}; no built-in machine has {letter}: describe one in a machine-data file (--machine FILE.toml)",
                machine.name
            )
        } else {
            format!(
                "machine `{}` has the axes {axes}; built-in machines with {letter}: {} (--machine NAME)",
                machine.name,
                with.join(", ")
            )
        };
        if !d.notes.contains(&note) {
            d.notes.push(note);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stanok_canon::Span;

    #[test]
    fn an_unconfigured_axis_names_the_machines_that_have_it() {
        let mut d = Diagnostic::error(
            "interp::axis-not-configured",
            "Bad character 'a' used (A axis is not configured on this machine)",
            Span::default(),
        );
        enrich(&mut d, &MachineData::default_mill());
        assert_eq!(d.notes.len(), 1);
        let note = &d.notes[0];
        assert!(note.starts_with("machine `mill` has the axes XYZ; built-in machines with A:"));
        assert!(
            note.contains("5axis-ab-head") && note.contains("beavermill"),
            "{note}"
        );
        assert!(!note.contains("5axis-bc-head,"), "{note}");
        // Once only.
        enrich(&mut d, &MachineData::default_mill());
        assert_eq!(d.notes.len(), 1);
    }
}
