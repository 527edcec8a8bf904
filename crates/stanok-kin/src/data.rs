//! The `[kinematics]` section of the machine-data TOML: which machine type, its rotary axes and
//! their geometry. `stanok-machine` embeds it in its machine data; [`KinematicsData::build`] turns it
//! into a [`FiveAxis`] (or reports that the machine is Cartesian).
//!
//! ```toml
//! [kinematics]
//! type = "head-head"          # cartesian | head-head | table-table | head-table | mill-turn
//! base = [0.0, 0.0, 1.0]      # spindle base vector (tool direction at zero rotary positions)
//! [[kinematics.rotary]]       # head axes outer → inner, then table axes outer → inner
//! name = "C"                  # A, B or C
//! carrier = "head"            # head | table
//! direction = [0.0, 0.0, 1.0] # at zero rotary positions, machine frame
//! point = [0.0, 0.0, 0.0]     # on the axis: head axes relative to the head reference point, table axes in machine coordinates
//! sign = 1.0                  # +1 right-hand rule (GOST 23597-79), −1 reversed
//! min = -inf                  # travel, deg
//! max = inf
//! max_velocity = 3600.0       # deg/min
//! ```
//!
//! Instead of `[[kinematics.rotary]]`, a Balt-System machine may give its characterization line:
//! `fat = "C,0,0,0,A,0,0,0"` (cvu-five-axis.md §4; see `fat.rs`).

use crate::{Carrier, FiveAxis, KinError, RotaryAxis};
use serde::{Deserialize, Serialize};

/// The kind of machine, as the `type` key names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum MachineType {
    /// No rotary orientation axes: the identity.
    Cartesian,
    /// Two head axes (TT).
    HeadHead,
    /// Two table axes (DD).
    TableTable,
    /// One table axis and one head axis (TD/DT).
    HeadTable,
    /// B head + C workpiece spindle, X on diameter (Mazatrol mill-turn).
    MillTurn,
}

/// The machine-data description of a machine's kinematics.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct KinematicsData {
    /// The machine type.
    #[serde(rename = "type")]
    pub kind: MachineType,
    /// Spindle base vector.
    #[serde(default = "plus_z")]
    pub base: [f64; 3],
    /// Joints X Y Z = head reference point − this, mm.
    #[serde(default)]
    pub linear_offset: [f64; 3],
    /// Whether the machine can switch tool-centre-point control on (AxiOMA error 654 if not).
    #[serde(default = "yes")]
    pub tcp_allowed: bool,
    /// The rotary orientation axes.
    #[serde(default)]
    pub rotary: Vec<RotaryAxis>,
    /// A Balt-System characterization line (the text after `FAT=`, cvu-five-axis.md §4.2):
    /// when given, it defines the rotary axes (machine data fills in their limits).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fat: Option<String>,
    /// Mazatrol tool tip point control: the frame X Y Z are programmed in (P12 bit 7 / F85 bit 2,
    /// mazatrol-tool-tip-control.md §4): `table` (0, default) or `workpiece` (1).
    #[serde(default)]
    pub ttpc_frame: TtpcFrame,
}

/// The Mazatrol TTPC programming frame (spec mazatrol §4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum TtpcFrame {
    /// Table coordinate system: glued to the table at the selection pose, turns with it.
    #[default]
    Table,
    /// Workpiece coordinate system: does not turn with the table; each block's end is given at
    /// that block's end table pose.
    Workpiece,
}

fn plus_z() -> [f64; 3] {
    [0.0, 0.0, 1.0]
}
fn yes() -> bool {
    true
}

impl KinematicsData {
    /// The machine, checked against its type: None for a Cartesian machine.
    pub fn build(&self) -> Result<Option<FiveAxis>, KinError> {
        if let (Some(fat), true) = (&self.fat, self.rotary.is_empty()) {
            let machine = crate::from_fat(fat).map_err(|e| {
                KinError::Degenerate(format!("FAT error {}: {}", e.code, e.message))
            })?;
            let data = KinematicsData {
                rotary: machine.rotary_axes().cloned().collect(),
                fat: None,
                ..self.clone()
            };
            return data.build();
        }
        let heads = self
            .rotary
            .iter()
            .filter(|a| a.carrier == Carrier::Head)
            .count();
        let tables = self.rotary.len() - heads;
        let expected = match self.kind {
            MachineType::Cartesian => (0, 0),
            MachineType::HeadHead => (2, 0),
            MachineType::TableTable => (0, 2),
            MachineType::HeadTable | MachineType::MillTurn => (1, 1),
        };
        if (heads, tables) != expected {
            return Err(KinError::Degenerate(format!(
                "a {:?} machine needs {} head and {} table rotary axes, the data gives {heads} and {tables}",
                self.kind, expected.0, expected.1
            )));
        }
        if self.kind == MachineType::Cartesian {
            return Ok(None);
        }
        let machine = FiveAxis::new(self.rotary.clone(), self.base)?
            .with_linear_offset(self.linear_offset)
            .with_x_diameter(self.kind == MachineType::MillTurn);
        Ok(Some(machine))
    }

    /// The data of a built machine's rotary axes (for `machine show`).
    pub fn axes(&self) -> &[RotaryAxis] {
        &self.rotary
    }
}
