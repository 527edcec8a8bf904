//! The state of the block being executed, as opposed to the block being prepared.
//!
//! The interpreter runs ahead of the machine by the planner's look-ahead (and, under cutter
//! compensation, by a block more), so its modal state belongs to a block that has not moved yet.
//! What the operator reads — the highlighted line, the DRO's G and M codes, feed, spindle, tool,
//! message — must be the block whose motion the axes are executing. So the state travels *with* the
//! motion, one way:
//!
//! ```text
//!  interpreter ─cmd─▶ machine thread: snapshot after cmd ──▶ ring[tag] ; cmd with span.line := tag
//!                                                                          │
//!  sink(setpoint) ◀── interpolator (setpoint.line = tag of its piece) ◀── SimMachine / motion stage
//!      └─ ring.at(tag): the snapshot of the executing command → status (line, DRO, message)
//! ```
//!
//! * Every command the machine thread hands to the simulated machine gets a **tag**: a number that
//!   increases by one per command (wrapping `u32`). The machine thread puts the tag where the
//!   motion stage carries a piece's source line (`Span::line`); the interpolator gives every
//!   setpoint the line of its piece, so the sink reads back the tag of the command being executed.
//!   Diagnostics of the simulated machine get their real line back before anyone sees them.
//! * The [`Snapshot`] after each command (the [`MachineState`] read off the accepted commands, the
//!   interpreter's G and M vectors, tool edge, the last message with its sequence number, the
//!   command's source line) goes into a **bounded ring**, keyed by tag. Consecutive commands that
//!   leave the same snapshot share it (an `Arc`), so the ring costs 16 bytes per command.
//! * The sink looks the tag of each setpoint up ([`SnapshotRing::executing`]): entries older than it
//!   are dropped (setpoints come in command order), the entry with the tag is the executing block.
//!   At a rest where everything has run (a program stop, single block, the end) the latest snapshot
//!   is the executing one ([`SnapshotRing::latest`]).
//!
//! Bounds: the ring holds at most [`RING_CAPACITY`] entries; past that (millions of commands
//! without motion between two setpoints) the oldest are dropped and their setpoints show the next
//! entry's state. Nothing flows back into the interpreter.
//!
//! Known approximation: under cutter compensation the interpreter reads one block ahead before it
//! releases a motion, so the G vector of a compensated move is read after the next block ran.

use crate::state::{ActiveCode, MachineState};
use serde::Serialize;
use std::collections::VecDeque;
use std::sync::Arc;

/// Most entries of the ring (module doc).
pub const RING_CAPACITY: usize = 1 << 18;

/// What the panel shows of one executing block (module doc).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Snapshot {
    /// Source line of the command.
    pub line: u32,
    /// Machine state after the command.
    pub state: MachineState,
    /// Active G codes (interpreter's vector after the command's block).
    pub g_codes: Vec<ActiveCode>,
    /// Active M functions.
    pub m_codes: Vec<ActiveCode>,
    /// Tool edge (D).
    pub edge: u8,
    /// The last operator message up to this command and its sequence number (1 = the run's
    /// first message); None before any.
    pub message: Option<(u64, String)>,
}

impl Snapshot {
    /// The same block state (ignoring the line and the position, which every motion changes).
    fn same_modes(&self, other: &Snapshot) -> bool {
        let mut a = self.state.clone();
        a.position = other.state.position;
        a == other.state
            && self.g_codes == other.g_codes
            && self.m_codes == other.m_codes
            && self.edge == other.edge
            && self.message == other.message
    }
}

/// `a` comes before `b` in the wrapping tag order.
fn before(a: u32, b: u32) -> bool {
    (a.wrapping_sub(b) as i32) < 0
}

/// The ring of the module doc.
#[derive(Debug)]
pub struct SnapshotRing {
    entries: VecDeque<(u32, Arc<Snapshot>)>,
    next_tag: u32,
    latest: Option<Arc<Snapshot>>,
    /// (first tag, line) at every change of line, the last [`RING_CAPACITY`]: the source line of
    /// a tag that has already executed (the stock's collisions come a few blocks late).
    lines: VecDeque<(u32, u32)>,
}

impl Default for SnapshotRing {
    fn default() -> Self {
        SnapshotRing {
            entries: VecDeque::new(),
            next_tag: 1,
            latest: None,
            lines: VecDeque::new(),
        }
    }
}

impl SnapshotRing {
    /// An empty ring.
    pub fn new() -> Self {
        SnapshotRing::default()
    }

    /// Records the snapshot after the next command and returns that command's tag. A snapshot
    /// equal to the previous one but for line and position is stored as a new entry only if the
    /// line differs; its state is shared otherwise.
    pub fn push(&mut self, snapshot: Snapshot) -> u32 {
        let tag = self.next_tag;
        self.next_tag = self.next_tag.wrapping_add(1);
        if self.lines.back().is_none_or(|&(_, l)| l != snapshot.line) {
            if self.lines.len() >= RING_CAPACITY {
                self.lines.pop_front();
            }
            self.lines.push_back((tag, snapshot.line));
        }
        let shared = match &self.latest {
            Some(prev) if prev.line == snapshot.line && prev.same_modes(&snapshot) => prev.clone(),
            _ => Arc::new(snapshot),
        };
        if self.entries.len() >= RING_CAPACITY {
            self.entries.pop_front();
        }
        self.entries.push_back((tag, shared.clone()));
        self.latest = Some(shared);
        tag
    }

    /// The snapshot of the command with `tag`, the executing one; older entries are dropped.
    /// None if the tag is not in the ring (then the caller keeps what it shows).
    pub fn executing(&mut self, tag: u32) -> Option<Arc<Snapshot>> {
        while let Some((t, _)) = self.entries.front() {
            if before(*t, tag) {
                self.entries.pop_front();
            } else {
                break;
            }
        }
        match self.entries.front() {
            Some((t, s)) if *t == tag => Some(s.clone()),
            _ => None,
        }
    }

    /// The source line of the command with `tag`, executed or not, while it is among the last
    /// [`RING_CAPACITY`] changes of line.
    pub fn line_of(&self, tag: u32) -> Option<u32> {
        let k = self.lines.partition_point(|&(t, _)| !before(tag, t));
        (k > 0).then(|| self.lines[k - 1].1)
    }

    /// The snapshot after the last command pushed (everything has run when the machine is at rest
    /// after a drain).
    pub fn latest(&self) -> Option<Arc<Snapshot>> {
        self.latest.clone()
    }

    /// Entries held.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// True when no entry is held.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn snap(line: u32, feed: f64) -> Snapshot {
        let mut state = MachineState {
            feed,
            ..MachineState::default()
        };
        state.position[0] = line as f64;
        Snapshot {
            line,
            state,
            g_codes: Vec::new(),
            m_codes: Vec::new(),
            edge: 0,
            message: None,
        }
    }

    #[test]
    fn setpoints_read_the_snapshot_of_their_own_command() {
        let mut ring = SnapshotRing::new();
        let a = ring.push(snap(1, 100.0));
        let b = ring.push(snap(2, 200.0));
        let c = ring.push(snap(3, 300.0));
        assert_eq!(ring.executing(a).unwrap().state.feed, 100.0);
        assert_eq!(ring.executing(a).unwrap().line, 1);
        assert_eq!(ring.executing(c).unwrap().state.feed, 300.0);
        // b was dropped on the way to c: setpoints never go back.
        assert!(ring.executing(b).is_none());
        assert_eq!(ring.latest().unwrap().line, 3);
        assert_eq!(ring.len(), 1);
    }

    #[test]
    fn the_line_of_an_executed_tag_is_still_known() {
        let mut ring = SnapshotRing::new();
        let a = ring.push(snap(1, 100.0));
        let b = ring.push(snap(2, 200.0));
        let b2 = ring.push(snap(2, 250.0));
        let c = ring.push(snap(7, 300.0));
        ring.executing(c);
        assert!(ring.executing(b).is_none());
        assert_eq!(
            [a, b, b2, c].map(|t| ring.line_of(t)),
            [Some(1), Some(2), Some(2), Some(7)]
        );
        assert_eq!(ring.line_of(0), None);
    }

    #[test]
    fn equal_states_on_one_line_share_their_snapshot() {
        let mut ring = SnapshotRing::new();
        let a = ring.push(snap(5, 100.0));
        let b = ring.push(snap(5, 100.0));
        let c = ring.push(snap(6, 100.0));
        let (sa, sb) = (ring.executing(a).unwrap(), ring.executing(b).unwrap());
        assert!(Arc::ptr_eq(&sa, &sb));
        assert_eq!(ring.executing(c).unwrap().line, 6);
    }

    #[test]
    fn tags_wrap_and_the_ring_is_bounded() {
        let mut ring = SnapshotRing::new();
        ring.next_tag = u32::MAX - 1;
        let a = ring.push(snap(1, 1.0));
        let b = ring.push(snap(2, 2.0));
        let c = ring.push(snap(3, 3.0));
        assert_eq!((a, b, c), (u32::MAX - 1, u32::MAX, 0));
        assert_eq!(ring.executing(c).unwrap().line, 3);
        for i in 0..(RING_CAPACITY + 10) {
            ring.push(snap(10 + i as u32, 0.0));
        }
        assert_eq!(ring.len(), RING_CAPACITY);
    }
}
