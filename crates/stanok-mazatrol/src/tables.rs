//! The control's tool and offset data as a program may change it (G10, #2001…, #5201…;
//! `docs/dialects/mazatrol-eia.md` §7.5, §15.6): a copy of the machine data's, with a
//! copy-on-write undo so that a failing block leaves it as it was.
//!
//! Work offsets: G54 … G59 are zero-offset systems 1 … 6, page 1; G54.1 P1 … P32 system 7 pages
//! 1 … 32, P33 … P48 system 8 pages 1 … 16 (the tables have 32 pages per system, `docs` D7).

use stanok_canon::setup::{ControlData, Tool, ToolEdge};

/// Tools and offsets of a run.
#[derive(Debug, Clone)]
pub struct Tables {
    /// The data.
    pub data: ControlData,
    /// The external (common) work offset, G10 L2 P0 (X Y Z A B C U V W, mm/deg).
    pub external: [f64; 9],
    saved: Option<Box<(ControlData, [f64; 9])>>,
}

impl Tables {
    /// The machine data's tables.
    pub fn new(control: &ControlData) -> Self {
        Tables {
            data: control.clone(),
            external: [0.0; 9],
            saved: None,
        }
    }

    /// A block starts.
    pub fn begin(&mut self) {
        self.saved = None;
    }

    /// Before the first write of a block: keep a copy for the rollback.
    pub fn touch(&mut self) {
        if self.saved.is_none() {
            self.saved = Some(Box::new((self.data.clone(), self.external)));
        }
    }

    /// Undoes the block's writes.
    pub fn rollback(&mut self) {
        if let Some(s) = self.saved.take() {
            let (d, e) = *s;
            self.data = d;
            self.external = e;
        }
    }

    /// (system index, page index) of G54.1 P n.
    fn extra_slot(p: u8) -> (usize, usize) {
        let i = (p.max(1) - 1) as usize;
        (6 + i / 32, i % 32)
    }

    /// Work offset of system 1 … 6 (G54 … G59), page 1.
    pub fn work_offset(&self, system: u8, page: u8) -> [f64; 9] {
        self.data
            .offsets
            .zero_offset(system, page)
            .map_or([0.0; 9], |z| z.offset.to_array())
    }

    /// G54.1 P n.
    pub fn extra_offset(&self, p: u8) -> [f64; 9] {
        let (s, pg) = Self::extra_slot(p);
        self.data
            .offsets
            .zero
            .get(s)
            .and_then(|v| v.get(pg))
            .map_or([0.0; 9], |z| z.offset.to_array())
    }

    /// Sets axis `axis` of a work offset (system 0 = external, 1…6) to `v` (call `touch` first).
    pub fn set_work_offset(&mut self, system: u8, axis: usize, v: f64) {
        if system == 0 {
            self.external[axis] = v;
            return;
        }
        if let Some(z) = self
            .data
            .offsets
            .zero
            .get_mut(system as usize - 1)
            .and_then(|p| p.get_mut(0))
        {
            let mut a = z.offset.to_array();
            a[axis] = v;
            z.offset = stanok_canon::Pose::from_array(a);
        }
    }

    /// Sets axis `axis` of G54.1 P n.
    pub fn set_extra_offset(&mut self, p: u8, axis: usize, v: f64) {
        let (s, pg) = Self::extra_slot(p);
        if let Some(z) = self
            .data
            .offsets
            .zero
            .get_mut(s)
            .and_then(|x| x.get_mut(pg))
        {
            let mut a = z.offset.to_array();
            a[axis] = v;
            z.offset = stanok_canon::Pose::from_array(a);
        }
    }

    /// The first edge of tool `n`, created (with zeros) if the tool is not in the table.
    pub fn edge_mut(&mut self, n: u32) -> &mut ToolEdge {
        let tool = self.data.tools.tools.entry(n).or_insert_with(|| Tool {
            number: n,
            pocket: 0,
            kind: Default::default(),
            edges: Vec::new(),
            comment: String::new(),
            body: Default::default(),
        });
        if tool.edges.is_empty() {
            tool.edges.push(ToolEdge::default());
        }
        &mut tool.edges[0]
    }

    /// The first edge of tool `n`.
    pub fn edge(&self, n: u32) -> Option<&ToolEdge> {
        self.data.tools.get(n).and_then(|t| t.edges.first())
    }

    /// True for a turning or grinding tool (X = L1, Z = L2 on the T-series).
    pub fn is_turning(&self, n: u32) -> bool {
        self.data.tools.get(n).is_some_and(|t| {
            matches!(
                t.kind,
                stanok_canon::setup::ToolKind::Turning | stanok_canon::setup::ToolKind::Grinding
            )
        })
    }

    /// The tool length of tool `n` (L1 + wear), 0 for an unknown tool.
    pub fn length(&self, n: u32) -> f64 {
        self.edge(n).map_or(0.0, |e| e.length[0] + e.length_wear[0])
    }

    /// The radius of tool `n` (radius + wear).
    pub fn radius(&self, n: u32) -> f64 {
        self.edge(n).map_or(0.0, |e| e.radius + e.radius_wear)
    }

    /// T-series offset `n`: (X radius, Z, nose radius, tip), geometry + wear.
    pub fn turn_offset(&self, n: u32) -> (f64, f64, f64, u8) {
        let Some(e) = self.edge(n) else {
            return (0.0, 0.0, 0.0, 0);
        };
        let (x, z) = if self.is_turning(n) {
            (
                e.length[0] + e.length_wear[0],
                e.length[1] + e.length_wear[1],
            )
        } else {
            (0.0, e.length[0] + e.length_wear[0])
        };
        (x, z, e.radius + e.radius_wear, e.orientation)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extra_offsets_map_to_systems_7_and_8() {
        assert_eq!(Tables::extra_slot(1), (6, 0));
        assert_eq!(Tables::extra_slot(32), (6, 31));
        assert_eq!(Tables::extra_slot(33), (7, 0));
        assert_eq!(Tables::extra_slot(48), (7, 15));
    }

    #[test]
    fn rollback_restores_tools_and_offsets() {
        let mut t = Tables::new(&ControlData::default());
        t.begin();
        t.touch();
        t.set_work_offset(1, 0, 5.0);
        t.edge_mut(7).length[0] = 3.0;
        t.set_extra_offset(40, 2, 1.0);
        t.external[1] = 2.0;
        t.rollback();
        assert_eq!(t.work_offset(1, 1)[0], 0.0);
        assert!(t.edge(7).is_none());
        assert_eq!(t.extra_offset(40)[2], 0.0);
        assert_eq!(t.external[1], 0.0);
    }
}
