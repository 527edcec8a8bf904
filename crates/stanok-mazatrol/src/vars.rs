//! The user variables of the custom macro (`docs/dialects/mazatrol-eia.md` §15.1): locals #1–#33
//! per macro level, commons #100–#199, non-volatile commons #500–#999, with a write journal so
//! that a failing block leaves every variable as it was.
//!
//! System variables (#1000 and above) live in the front end, which knows the state they show.

use crate::macro_b::MVal;
use std::collections::BTreeMap;

/// Locals of one macro level.
pub type Locals = [MVal; 33];

/// Deepest nesting of G65/G66 calls (the main program's level not counted) [F].
pub const MAX_MACRO_LEVELS: usize = 4;

/// What a write replaced (for the rollback).
#[derive(Debug, Clone, PartialEq)]
enum Undo {
    Local { index: usize, old: MVal },
    Common { index: usize, old: MVal },
    Perm { index: usize, old: MVal },
    Pushed,
    Popped(Box<Locals>),
}

/// Which user variable a number is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// #0.
    Vacant,
    /// #1–#33 (index 0–32).
    Local(usize),
    /// #100–#199 (index 0–99).
    Common(usize),
    /// #500–#999 (index 0–499).
    Perm(usize),
}

/// Classifies a user variable number; `None` for system variables and unknown numbers.
pub fn kind(n: u32) -> Option<Kind> {
    match n {
        0 => Some(Kind::Vacant),
        1..=33 => Some(Kind::Local(n as usize - 1)),
        100..=199 => Some(Kind::Common(n as usize - 100)),
        500..=999 => Some(Kind::Perm(n as usize - 500)),
        _ => None,
    }
}

/// The user variables of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct Variables {
    levels: Vec<Locals>,
    common: [MVal; 100],
    perm: Box<[MVal; 500]>,
    journal: Vec<Undo>,
}

impl Default for Variables {
    fn default() -> Self {
        Variables {
            levels: vec![[None; 33]],
            common: [None; 100],
            perm: Box::new([None; 500]),
            journal: Vec::new(),
        }
    }
}

impl Variables {
    /// Variables at the start of a run: #500–#999 from the stored values (keys 500…999).
    pub fn new(stored: &BTreeMap<u32, f64>) -> Self {
        let mut v = Variables::default();
        for (&n, &x) in stored.range(500..=999) {
            v.perm[n as usize - 500] = Some(x);
        }
        v
    }

    /// The non-volatile values to store after the run (vacant ones left out).
    pub fn stored(&self) -> BTreeMap<u32, f64> {
        self.perm
            .iter()
            .enumerate()
            .filter_map(|(i, v)| v.map(|x| (500 + i as u32, x)))
            .collect()
    }

    /// The current macro level (0 = the main program).
    pub fn level(&self) -> usize {
        self.levels.len() - 1
    }

    /// A user variable's value.
    pub fn get(&self, k: Kind) -> MVal {
        match k {
            Kind::Vacant => None,
            Kind::Local(i) => self.levels.last().and_then(|l| l[i]),
            Kind::Common(i) => self.common[i],
            Kind::Perm(i) => self.perm[i],
        }
    }

    /// Writes a user variable (journalled). Writing #0 is refused by the caller.
    pub fn set(&mut self, k: Kind, v: MVal) {
        match k {
            Kind::Vacant => {}
            Kind::Local(index) => {
                if let Some(l) = self.levels.last_mut() {
                    self.journal.push(Undo::Local {
                        index,
                        old: l[index],
                    });
                    l[index] = v;
                }
            }
            Kind::Common(index) => {
                self.journal.push(Undo::Common {
                    index,
                    old: self.common[index],
                });
                self.common[index] = v;
            }
            Kind::Perm(index) => {
                self.journal.push(Undo::Perm {
                    index,
                    old: self.perm[index],
                });
                self.perm[index] = v;
            }
        }
    }

    /// Enters a macro level with these locals (G65/G66). False when the levels are exhausted.
    pub fn push(&mut self, locals: Locals) -> bool {
        if self.level() >= MAX_MACRO_LEVELS {
            return false;
        }
        self.levels.push(locals);
        self.journal.push(Undo::Pushed);
        true
    }

    /// Leaves a macro level (M99 of a macro); the main level stays.
    pub fn pop(&mut self) {
        if self.levels.len() > 1 {
            if let Some(l) = self.levels.pop() {
                self.journal.push(Undo::Popped(Box::new(l)));
            }
        }
    }

    /// Starts a block: the journal is empty.
    pub fn begin(&mut self) {
        self.journal.clear();
    }

    /// Undoes every write since `begin`.
    pub fn rollback(&mut self) {
        while let Some(u) = self.journal.pop() {
            match u {
                Undo::Local { index, old } => {
                    if let Some(l) = self.levels.last_mut() {
                        l[index] = old;
                    }
                }
                Undo::Common { index, old } => self.common[index] = old,
                Undo::Perm { index, old } => self.perm[index] = old,
                Undo::Pushed => {
                    self.levels.pop();
                }
                Undo::Popped(l) => self.levels.push(*l),
            }
        }
    }

    /// Keeps the writes since `begin`.
    pub fn commit(&mut self) {
        self.journal.clear();
    }

    /// Program end: locals and #100–#199 vacant, levels back to the main program (#500–#999 stay).
    pub fn reset(&mut self) {
        self.levels.truncate(1);
        self.levels[0] = [None; 33];
        self.common = [None; 100];
        self.journal.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classify() {
        assert_eq!(kind(0), Some(Kind::Vacant));
        assert_eq!(kind(1), Some(Kind::Local(0)));
        assert_eq!(kind(33), Some(Kind::Local(32)));
        assert_eq!(kind(34), None);
        assert_eq!(kind(100), Some(Kind::Common(0)));
        assert_eq!(kind(199), Some(Kind::Common(99)));
        assert_eq!(kind(200), None);
        assert_eq!(kind(500), Some(Kind::Perm(0)));
        assert_eq!(kind(999), Some(Kind::Perm(499)));
        assert_eq!(kind(1000), None);
    }

    #[test]
    fn a_rolled_back_block_leaves_nothing() {
        let mut v = Variables::new(&BTreeMap::from([(500, 1.5), (12, 9.0)]));
        assert_eq!(v.get(Kind::Perm(0)), Some(1.5));
        v.begin();
        v.set(Kind::Local(0), Some(1.0));
        v.commit();
        let before = v.clone();
        v.begin();
        v.set(Kind::Local(0), Some(2.0));
        v.set(Kind::Common(5), Some(3.0));
        v.set(Kind::Perm(1), Some(4.0));
        assert!(v.push([Some(7.0); 33]));
        v.set(Kind::Local(2), None);
        v.pop();
        v.rollback();
        assert_eq!(v, before);
    }

    #[test]
    fn levels_are_bounded_and_locals_are_per_level() {
        let mut v = Variables::default();
        v.set(Kind::Local(0), Some(1.0));
        for i in 0..MAX_MACRO_LEVELS {
            assert!(v.push([None; 33]), "level {i}");
            assert_eq!(v.get(Kind::Local(0)), None);
        }
        assert!(!v.push([None; 33]));
        for _ in 0..MAX_MACRO_LEVELS {
            v.pop();
        }
        assert_eq!(v.get(Kind::Local(0)), Some(1.0));
        v.pop();
        assert_eq!(v.level(), 0);
    }

    #[test]
    fn stored_values_round_trip_and_reset_keeps_them() {
        let mut v = Variables::default();
        v.set(Kind::Perm(499), Some(-2.0));
        v.set(Kind::Common(0), Some(1.0));
        v.reset();
        assert_eq!(v.stored(), BTreeMap::from([(999, -2.0)]));
        assert_eq!(v.get(Kind::Common(0)), None);
    }
}
