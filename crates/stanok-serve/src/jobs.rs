//! Work a request starts (checking, loading, previewing a program) runs here: never on an HTTP
//! worker, always under a budget, and never longer than its client waits.
//!
//! ## How a job runs
//! * **Its own thread, with a known stack** ([`JOB_STACK_BYTES`]). Deeply nested input recurses in
//!   the parser and the evaluator; on a tokio worker (2 MB) 5,000 chained terms overflowed the stack,
//!   and a stack overflow aborts the whole process. The job thread's stack is large enough for the
//!   longest line the upload limit allows in practice, and a panic in the job is caught
//!   (`catch_unwind`) and answered as an error: the panel survives either way.
//! * **A slot** ([`MAX_CONCURRENT_JOBS`], one per core): a thread holds its slot until it has
//!   really ended — a cancelled job that is still unwinding keeps it — so repeated requests can
//!   never take more than that many cores.
//! * **A wall-time budget** ([`JobLimits::wall`]): when it is over, the request is answered with a
//!   diagnostic naming the budget and the job is cancelled.
//! * **Cancellation** ([`Cancel`]): the handler's future owns a guard that raises the job's flag
//!   when it is dropped — when the job ends, when the budget is over, and when the client goes away
//!   (hyper drops the future of a closed connection). The job looks at the flag where its work
//!   is: every line the interpreter reads ([`CancelReader`]: every block, loops included, reads its
//!   line) and every setpoint the simulated machine produces. On the flag it unwinds with
//!   [`Cancelled`] (`resume_unwind`: no panic message), which `catch_unwind` turns into the end of
//!   the job. This is how rust-analyzer's salsa cancels queries; nothing of a cancelled job is used.
//! * **Memory** is bounded by construction: the program text by the upload limit (or
//!   [`MAX_PROGRAM_BYTES`] for a file), the preview by its point budget, the diagnostics by the
//!   interpreter's error limit and [`MAX_WARNINGS`].

use std::io::{BufRead, Read, Seek, SeekFrom};
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::{oneshot, OwnedSemaphorePermit, Semaphore};

/// Stack of a job thread, bytes (virtual: pages are only touched as deep as the work goes).
pub const JOB_STACK_BYTES: usize = 256 * 1024 * 1024;

/// Jobs running at once (the machine has two cores; the machine thread has its own).
pub const MAX_CONCURRENT_JOBS: usize = 2;

/// Largest program file the panel loads by name, bytes.
pub const MAX_PROGRAM_BYTES: u64 = 512 * 1024 * 1024;

/// Most warnings a check returns (errors are bounded by the interpreter's `max_errors`).
pub const MAX_WARNINGS: usize = 500;

/// Budgets of one job.
#[derive(Debug, Clone, Copy)]
pub struct JobLimits {
    /// Wall time from the request until the answer, s.
    pub wall: Duration,
}

impl Default for JobLimits {
    /// 60 s: a 10-million-block program loads well within it on an optimised build.
    fn default() -> Self {
        JobLimits {
            wall: Duration::from_secs(60),
        }
    }
}

/// The unwinding payload of a cancelled job (module doc).
#[derive(Debug)]
pub struct Cancelled;

/// A job's cancellation flag (module doc).
#[derive(Debug, Clone, Default)]
pub struct Cancel(Arc<AtomicBool>);

impl Cancel {
    /// A flag that is not raised.
    pub fn new() -> Self {
        Cancel::default()
    }

    /// Raises the flag.
    pub fn raise(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Lowers the flag (a stop switch released by the next cycle start).
    pub fn lower(&self) {
        self.0.store(false, Ordering::Relaxed);
    }

    /// True once raised.
    pub fn is_raised(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// Unwinds with [`Cancelled`] if the flag is raised (call it only inside a job or another
    /// `catch_unwind` that expects it).
    #[inline]
    pub fn check(&self) {
        if self.is_raised() {
            resume_unwind(Box::new(Cancelled));
        }
    }
}

/// Raises the flag when dropped (module doc).
struct RaiseOnDrop(Cancel);

impl Drop for RaiseOnDrop {
    fn drop(&mut self) {
        self.0.raise();
    }
}

/// Why a job gave no result.
#[derive(Debug, Clone, PartialEq)]
pub enum JobError {
    /// The wall-time budget was over, s.
    Budget(f64),
    /// The job panicked (a bug); the message.
    Panicked(String),
}

impl std::fmt::Display for JobError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            JobError::Budget(s) => write!(
                f,
                "the panel's time budget of {s} s for this request was used up before the program \
                 was read to its end (serve --job-budget)"
            ),
            JobError::Panicked(m) => write!(f, "internal error while reading the program: {m}"),
        }
    }
}

/// The job slots and limits of one panel.
#[derive(Debug)]
pub struct Jobs {
    slots: Arc<Semaphore>,
    limits: JobLimits,
}

impl Jobs {
    /// Slots for [`MAX_CONCURRENT_JOBS`] jobs under `limits`.
    pub fn new(limits: JobLimits) -> Self {
        Jobs {
            slots: Arc::new(Semaphore::new(MAX_CONCURRENT_JOBS)),
            limits,
        }
    }

    /// Runs `work` as a job (module doc) and returns its result. Dropping the returned future
    /// cancels the job.
    pub async fn run<T, F>(&self, work: F) -> Result<T, JobError>
    where
        T: Send + 'static,
        F: FnOnce(&Cancel) -> T + Send + 'static,
    {
        let cancel = Cancel::new();
        let _guard = RaiseOnDrop(cancel.clone());
        let budget = self.limits.wall;
        let job = async {
            let Ok(permit) = self.slots.clone().acquire_owned().await else {
                return Err(JobError::Panicked("the job slots are closed".into()));
            };
            let (tx, rx) = oneshot::channel();
            spawn(permit, cancel.clone(), work, tx)?;
            match rx.await {
                Ok(r) => r,
                Err(_) => Err(JobError::Panicked("the job ended without an answer".into())),
            }
        };
        match tokio::time::timeout(budget, job).await {
            Ok(r) => r,
            Err(_) => Err(JobError::Budget(budget.as_secs_f64())),
        }
    }
}

/// Starts the job thread; it keeps `permit` until it ends.
fn spawn<T, F>(
    permit: OwnedSemaphorePermit,
    cancel: Cancel,
    work: F,
    tx: oneshot::Sender<Result<T, JobError>>,
) -> Result<(), JobError>
where
    T: Send + 'static,
    F: FnOnce(&Cancel) -> T + Send + 'static,
{
    std::thread::Builder::new()
        .name("stanok-job".into())
        .stack_size(JOB_STACK_BYTES)
        .spawn(move || {
            let _permit = permit;
            let result = catch_unwind(AssertUnwindSafe(|| work(&cancel)));
            let answer = match result {
                Ok(v) => Ok(v),
                Err(payload) if payload.is::<Cancelled>() => return,
                Err(payload) => Err(JobError::Panicked(panic_text(&*payload))),
            };
            let _ = tx.send(answer);
        })
        .map(|_| ())
        .map_err(|e| JobError::Panicked(format!("cannot start a job thread: {e}")))
}

/// The message of a panic payload.
pub fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        s.to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "panic".into()
    }
}

/// Program text as the interpreter's source, looking at the cancel flag on every read (module
/// doc). `Cursor` semantics otherwise.
#[derive(Debug, Clone)]
pub struct CancelReader {
    text: Arc<str>,
    pos: usize,
    cancel: Cancel,
}

impl CancelReader {
    /// A reader of `text` from its start.
    pub fn new(text: Arc<str>, cancel: Cancel) -> Self {
        CancelReader {
            text,
            pos: 0,
            cancel,
        }
    }
}

impl Read for CancelReader {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = {
            let avail = self.fill_buf()?;
            let n = avail.len().min(buf.len());
            buf[..n].copy_from_slice(&avail[..n]);
            n
        };
        self.consume(n);
        Ok(n)
    }
}

impl BufRead for CancelReader {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        self.cancel.check();
        let bytes = self.text.as_bytes();
        Ok(&bytes[self.pos.min(bytes.len())..])
    }

    fn consume(&mut self, amt: usize) {
        self.pos = (self.pos + amt).min(self.text.len());
    }
}

impl Seek for CancelReader {
    fn seek(&mut self, to: SeekFrom) -> std::io::Result<u64> {
        let len = self.text.len() as i128;
        let target = match to {
            SeekFrom::Start(n) => n as i128,
            SeekFrom::End(d) => len + d as i128,
            SeekFrom::Current(d) => self.pos as i128 + d as i128,
        };
        if target < 0 {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "seek before the start of the program",
            ));
        }
        self.pos = target.min(len) as usize;
        Ok(self.pos as u64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reader_reads_and_seeks_like_a_cursor_and_unwinds_when_cancelled() {
        let cancel = Cancel::new();
        let mut r = CancelReader::new("G0 X1\nG0 X2\n".into(), cancel.clone());
        let mut line = String::new();
        r.read_line(&mut line).unwrap();
        assert_eq!(line, "G0 X1\n");
        r.seek(SeekFrom::Start(0)).unwrap();
        let mut all = String::new();
        r.read_to_string(&mut all).unwrap();
        assert_eq!(all, "G0 X1\nG0 X2\n");
        assert!(r.seek(SeekFrom::Current(-100)).is_err());
        cancel.raise();
        let caught = catch_unwind(AssertUnwindSafe(|| {
            let mut s = String::new();
            let _ = r.read_line(&mut s);
        }));
        assert!(caught.unwrap_err().is::<Cancelled>());
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 1)]
    async fn a_job_answers_survives_a_panic_and_is_cut_at_its_budget() {
        let jobs = Jobs::new(JobLimits {
            wall: Duration::from_secs(20),
        });
        assert_eq!(jobs.run(|_| 41 + 1).await, Ok(42));
        let r: Result<(), _> = jobs.run(|_| panic!("boom")).await;
        assert_eq!(r, Err(JobError::Panicked("boom".into())));
        let jobs = Jobs::new(JobLimits {
            wall: Duration::from_millis(300),
        });
        // A job that spins, looking at its flag: answered at the budget, and it ends (its slot
        // comes back, so two more jobs still run).
        let spun = Arc::new(AtomicBool::new(false));
        let s2 = spun.clone();
        let r = jobs
            .run(move |c| loop {
                s2.store(true, Ordering::Relaxed);
                c.check();
                std::thread::sleep(Duration::from_millis(1));
            })
            .await;
        assert!(matches!(r, Err(JobError::Budget(_))));
        assert!(spun.load(Ordering::Relaxed));
        for _ in 0..3 {
            assert_eq!(jobs.run(|_| 1).await, Ok(1));
        }
    }

    #[test]
    fn a_deep_recursion_fits_the_job_stack() {
        fn depth(n: u32) -> u32 {
            // A frame of over 512 bytes that the optimiser cannot drop.
            let pad = std::hint::black_box([n as u8; 512]);
            if n == 0 {
                0
            } else {
                1 + depth(n - 1) + u32::from(pad[0] == 0 && n == u32::MAX)
            }
        }
        let rt = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .unwrap();
        // 100,000 frames of over 512 bytes: far beyond a worker's 2 MB.
        let r = rt.block_on(Jobs::new(JobLimits::default()).run(|_| depth(100_000)));
        assert_eq!(r, Ok(100_000));
    }
}
