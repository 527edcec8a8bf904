//! Machine data written back as TOML (`stanok machine show --toml`): the keys as read, stored
//! data sparsely.

use super::*;

impl MachineData {
    /// The machine data as TOML that [`MachineData::from_toml_str`] reads back to the same value;
    /// the stored data is written sparsely ([`crate::control::control_to_toml`]).
    pub fn to_toml(&self) -> String {
        let (control_keys, control_tables) = control_toml_parts(&self.control);
        let mut out = String::new();
        let _ = writeln!(out, "name = {}", toml_string(&self.name));
        if !self.description.is_empty() {
            let _ = writeln!(out, "description = {}", toml_string(&self.description));
        }
        let _ = writeln!(out, "rapid_rate = {}", toml_float(self.rapid_rate));
        let _ = writeln!(out, "max_feed = {}", toml_float(self.max_feed));
        let _ = writeln!(out, "arc_tolerance = {}", toml_float(self.arc_tolerance));
        let _ = writeln!(out, "path_tolerance = {}", toml_float(self.path_tolerance));
        let units = match self.linuxcnc_units {
            LengthUnits::Millimetres => "mm",
            LengthUnits::Inches => "inch",
        };
        let _ = writeln!(out, "linuxcnc_units = \"{units}\"");
        if self.m_functions != "generic" {
            let _ = writeln!(out, "m_functions = {}", toml_string(&self.m_functions));
        }
        out.push_str(&control_keys);
        for (name, table) in [
            ("feed_table", &self.feed_table),
            ("speed_table", &self.speed_table),
        ] {
            if !table.is_empty() {
                let _ = writeln!(out, "\n[{name}]");
                for (i, v) in table {
                    let _ = writeln!(out, "{i} = {}", toml_float(*v));
                }
            }
        }
        for a in &self.axes {
            let kind = match a.kind {
                AxisKind::Linear => "linear",
                AxisKind::Rotary => "rotary",
            };
            let _ = writeln!(
                out,
                "\n[[axis]]\nname = \"{}\"\nkind = \"{kind}\"\nmin = {}\nmax = {}\nmax_velocity = {}\n\
                 max_acceleration = {}\nmax_jerk = {}",
                a.name,
                toml_float(a.min),
                toml_float(a.max),
                toml_float(a.max_velocity),
                toml_float(a.max_acceleration),
                toml_float(a.max_jerk)
            );
            if a.transverse {
                out.push_str("transverse = true\n");
            }
        }
        if let Some(k) = &self.kinematics {
            #[derive(Serialize)]
            struct Section<'a> {
                kinematics: &'a KinematicsData,
            }
            if let Ok(text) = toml::to_string(&Section { kinematics: k }) {
                out.push('\n');
                out.push_str(&text);
            }
        }
        if let Some(m) = &self.mazatrol {
            #[derive(Serialize)]
            struct Section<'a> {
                mazatrol: &'a MazatrolData,
            }
            if let Ok(text) = toml::to_string(&Section { mazatrol: m }) {
                out.push('\n');
                out.push_str(&text);
            }
        }
        if let Some(st) = &self.stock {
            stock::write(&mut out, st);
        }
        if !control_tables.is_empty() {
            out.push('\n');
            out.push_str(&control_tables);
        }
        out
    }
}
