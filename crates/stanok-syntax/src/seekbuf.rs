//! A buffered reader whose seeks inside its buffer cost nothing.
//!
//! `std::io::BufReader` discards its buffer on every seek, so each pass of a loop — the
//! interpreter jumps back to the loop's first line (`BlockReader::seek`) — costs a system call to
//! move the file position and another to refill the buffer, even when the whole loop lies in the
//! buffer. [`SeekBufReader`] remembers which file bytes its buffer holds: a seek to a position
//! inside them only moves the cursor. A seek elsewhere (or a file that changed under it: it is
//! not re-read) seeks the inner reader and empties the buffer, as `BufReader` does.
//!
//! Invariant: `buf[..filled]` are the bytes of the inner reader at offsets
//! `start .. start + filled`, and the inner reader's position is `start + filled`; the logical
//! position is `start + pos`.

use std::io::{BufRead, Read, Result, Seek, SeekFrom};

/// Buffer size: 64 KiB (a loop of a few hundred lines stays inside it).
const CAPACITY: usize = 64 * 1024;

/// A buffered reader with cheap seeks within its buffer (module doc).
#[derive(Debug)]
pub struct SeekBufReader<R> {
    inner: R,
    buf: Box<[u8]>,
    /// File offset of `buf[0]`.
    start: u64,
    /// Valid bytes in `buf`.
    filled: usize,
    /// The cursor in `buf`.
    pos: usize,
}

impl<R: Read + Seek> SeekBufReader<R> {
    /// A reader at `inner`'s current position, taken as offset 0 if it cannot tell.
    pub fn new(mut inner: R) -> Self {
        let start = inner.stream_position().unwrap_or(0);
        SeekBufReader {
            inner,
            buf: vec![0; CAPACITY].into_boxed_slice(),
            start,
            filled: 0,
            pos: 0,
        }
    }
}

impl<R: Read + Seek> Read for SeekBufReader<R> {
    fn read(&mut self, out: &mut [u8]) -> Result<usize> {
        let available = self.fill_buf()?;
        let n = available.len().min(out.len());
        out[..n].copy_from_slice(&available[..n]);
        self.consume(n);
        Ok(n)
    }
}

impl<R: Read + Seek> BufRead for SeekBufReader<R> {
    fn fill_buf(&mut self) -> Result<&[u8]> {
        if self.pos >= self.filled {
            self.start += self.filled as u64;
            self.filled = 0;
            self.pos = 0;
            self.filled = self.inner.read(&mut self.buf)?;
        }
        Ok(&self.buf[self.pos..self.filled])
    }

    fn consume(&mut self, amount: usize) {
        self.pos = (self.pos + amount).min(self.filled);
    }
}

impl<R: Read + Seek> Seek for SeekBufReader<R> {
    fn seek(&mut self, to: SeekFrom) -> Result<u64> {
        let target = match to {
            SeekFrom::Start(p) => Some(p),
            SeekFrom::Current(d) => (self.start + self.pos as u64).checked_add_signed(d),
            SeekFrom::End(_) => None,
        };
        if let Some(p) = target {
            if p >= self.start && p <= self.start + self.filled as u64 {
                self.pos = (p - self.start) as usize;
                return Ok(p);
            }
        }
        // Outside the buffer: as `BufReader` (a relative seek is made absolute first, since the
        // inner reader stands at the buffer's end).
        let to = match (to, target) {
            (SeekFrom::Current(_), Some(p)) => SeekFrom::Start(p),
            _ => to,
        };
        let p = self.inner.seek(to)?;
        self.start = p;
        self.filled = 0;
        self.pos = 0;
        Ok(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Cursor;

    /// Reads and seeks agree with the plain bytes, inside and outside the buffer.
    #[test]
    fn reads_and_seeks_like_the_bytes() {
        let data: Vec<u8> = (0..200_000u32).map(|i| (i % 251) as u8).collect();
        let mut r = SeekBufReader::new(Cursor::new(data.clone()));
        let mut b = [0u8; 10];
        r.read_exact(&mut b).unwrap();
        assert_eq!(&b, &data[..10]);
        for &p in &[5u64, 0, 70_000, 69_990, 150_000, 3, 199_995] {
            assert_eq!(r.seek(SeekFrom::Start(p)).unwrap(), p);
            let mut b = [0u8; 5];
            r.read_exact(&mut b).unwrap();
            assert_eq!(&b, &data[p as usize..p as usize + 5], "at {p}");
        }
        r.seek(SeekFrom::Start(100)).unwrap();
        assert_eq!(r.seek(SeekFrom::Current(-50)).unwrap(), 50);
        let mut rest = Vec::new();
        r.read_to_end(&mut rest).unwrap();
        assert_eq!(rest, &data[50..]);
    }
}
