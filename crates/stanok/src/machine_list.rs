//! `stanok machine list`: the built-in machines, one line each (name, axes, kinematics,
//! description), or as JSON.

use serde::Serialize;
use stanok_kin::MachineType;
use stanok_machine::{MachineData, BUILTIN_MACHINES};
use std::fmt::Write;

/// One built-in machine as listed.
#[derive(Debug, Serialize)]
pub struct Entry {
    /// `--machine` name.
    pub name: String,
    /// Axis letters in the machine's order.
    pub axes: String,
    /// `cartesian`, `lathe`, `head-head`, `table-table`, `head-table`, `mill-turn`.
    pub kinematics: &'static str,
    /// One line for people.
    pub description: String,
}

/// The kinematics of a machine in a word.
pub fn kinematics_name(m: &MachineData) -> &'static str {
    match m.kinematics.as_ref().map(|k| k.kind) {
        Some(MachineType::HeadHead) => "head-head",
        Some(MachineType::TableTable) => "table-table",
        Some(MachineType::HeadTable) => "head-table",
        Some(MachineType::MillTurn) => "mill-turn",
        Some(MachineType::Cartesian) | None if m.is_lathe() => "lathe",
        Some(MachineType::Cartesian) | None => "cartesian",
    }
}

/// Every built-in machine.
pub fn entries() -> Vec<Entry> {
    BUILTIN_MACHINES
        .iter()
        .filter_map(|name| MachineData::builtin(name))
        .map(|m| Entry {
            axes: m.axes.iter().map(|a| a.name).collect(),
            kinematics: kinematics_name(&m),
            description: m.description.clone(),
            name: m.name,
        })
        .collect()
}

/// The list as text: a header and one aligned line per machine.
pub fn text() -> String {
    let list = entries();
    let width = list.iter().map(|e| e.name.len()).max().unwrap_or(4).max(4);
    let axes = list.iter().map(|e| e.axes.len()).max().unwrap_or(4).max(4);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:width$}  {:axes$}  {:11}  description",
        "name", "axes", "kinematics"
    );
    for e in &list {
        let _ = writeln!(
            s,
            "{:width$}  {:axes$}  {:11}  {}",
            e.name, e.axes, e.kinematics, e.description
        );
    }
    s.push_str("\nUse one with --machine NAME; `stanok machine show --machine NAME` prints all of its data.\n");
    s
}

/// The list as JSON.
pub fn json() -> String {
    serde_json::to_string_pretty(&entries()).unwrap_or_default() + "\n"
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_list_names_every_builtin_machine_with_its_axes_and_kinematics() {
        let list = entries();
        assert_eq!(list.len(), BUILTIN_MACHINES.len());
        let get = |n: &str| list.iter().find(|e| e.name == n).unwrap();
        assert_eq!(get("mill").axes, "XYZ");
        assert_eq!(get("mill").kinematics, "cartesian");
        assert_eq!(get("lathe").axes, "XZ");
        assert_eq!(get("lathe").kinematics, "lathe");
        assert_eq!(get("5axis-bc-head").kinematics, "head-head");
        assert_eq!(get("5axis-ac-table").kinematics, "table-table");
        assert_eq!(get("millturn-bc").kinematics, "mill-turn");
    }
}
