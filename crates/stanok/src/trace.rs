//! `stanok run --trace FILE`: the servo-rate setpoints as CSV, streamed to the file.
//!
//! Header `t,X,Y,Z[,A,B,C,U,V,W],S,line` with the machine's axes in X Y Z A B C U V W order; one
//! line per setpoint: time in seconds, positions in mm or degrees, six decimals (1 ns / 1 µdeg);
//! S the main spindle's speed in rev/min, signed by its direction (M3 +, M4 −, 0 after M5);
//! `line` the source line of the block being executed. Nothing is
//! kept in memory: each line goes through a `BufWriter`. The first write error is kept and reported
//! by [`TraceWriter::close`]; writing stops after it.

use crate::progress::Progress;
use stanok_machine::{MachineData, SetpointSink};
use std::cell::RefCell;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::rc::Rc;

struct State {
    out: BufWriter<File>,
    axes: Vec<usize>,
    error: Option<std::io::Error>,
}

/// A CSV trace file being written (cheap to clone: one shared writer).
#[derive(Clone)]
pub struct TraceWriter {
    path: PathBuf,
    state: Rc<RefCell<State>>,
}

impl TraceWriter {
    /// Creates the file and writes the header.
    pub fn create(path: &Path, machine: &MachineData) -> Result<Self, String> {
        let file =
            File::create(path).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        let mut axes: Vec<usize> = machine.axes.iter().map(|a| a.pose_index()).collect();
        axes.sort_unstable();
        axes.dedup();
        let mut out = BufWriter::new(file);
        let mut header = String::from("t");
        for &i in &axes {
            header.push(',');
            header.push(stanok_canon::AXIS_LETTERS[i]);
        }
        header.push_str(",S,line\n");
        let error = out.write_all(header.as_bytes()).err();
        Ok(TraceWriter {
            path: path.to_path_buf(),
            state: Rc::new(RefCell::new(State { out, axes, error })),
        })
    }

    fn write(&self, sp: &stanok_machine::Setpoint) {
        let mut st = self.state.borrow_mut();
        if st.error.is_some() {
            return;
        }
        let State { out, axes, error } = &mut *st;
        let mut result = write!(out, "{:.6}", sp.t);
        for &i in axes.iter() {
            result = result.and_then(|_| write!(out, ",{:.6}", sp.position[i]));
        }
        let s = sp.spindle_rpm[0] * f64::from(sp.spindle_dir[0]);
        result = result.and_then(|_| write!(out, ",{:.3},{}", s, sp.line));
        if let Err(e) = result.and_then(|_| out.write_all(b"\n")) {
            *error = Some(e);
        }
    }

    /// Flushes the file; reports the first write error.
    pub fn close(&self) -> Result<(), String> {
        let mut st = self.state.borrow_mut();
        let flushed = st.out.flush();
        match st.error.take().map_or(flushed, Err) {
            Ok(()) => Ok(()),
            Err(e) => Err(format!("cannot write {}: {e}", self.path.display())),
        }
    }
}

/// The simulated machine's setpoint sink: the trace file (if any) and the progress display.
pub fn sink(trace: Option<TraceWriter>, progress: Progress) -> SetpointSink {
    Box::new(move |sp| {
        if let Some(t) = &trace {
            t.write(sp);
        }
        progress.setpoint(sp.t);
    })
}
