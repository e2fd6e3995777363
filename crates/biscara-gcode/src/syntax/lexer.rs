//! Lines and their significant characters.
//!
//! LinuxCNC reads a block by first dropping spaces and tabs everywhere and lowering the case of
//! everything outside comments (`close_and_downcase`); then it parses words from what is left.
//! [`compact`](crate::syntax::lexer::compact) does the same into reused buffers, keeping for
//! every byte left its column in the original line (for error messages). A `( … )` comment
//! becomes one `(` byte, so that it still separates what stands on either side of it, as it
//! does in LinuxCNC.

use std::io::{self, BufRead, BufReader, Read, Seek};

/// LinuxCNC refuses lines longer than this ("Command too long").
pub(crate) const MAX_LINE: usize = 252;
/// The UTF-8 byte-order mark, skipped at the start of a file.
pub(crate) const UTF8_BOM: &[u8] = b"\xef\xbb\xbf";

/// Where a problem is (byte offsets into the raw line) and what it is.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Fault {
    /// First byte (0-based) within the raw line.
    pub start: usize,
    /// One past the last byte.
    pub end: usize,
    /// What kind of problem.
    pub kind: FaultKind,
    /// The message.
    pub message: String,
}

/// The kinds of [`Fault`], mapped onto [`crate::GcodeError`] variants.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum FaultKind {
    Syntax,
    Invalid,
    NotSupported { code: String, note: &'static str },
    Cannot { code: String, reason: &'static str },
    ForeignAxis(char),
    Needs(crate::error::Setting),
}

impl Fault {
    pub(crate) fn syntax(start: usize, end: usize, message: impl Into<String>) -> Fault {
        Fault { start, end, kind: FaultKind::Syntax, message: message.into() }
    }

    pub(crate) fn invalid(start: usize, end: usize, message: impl Into<String>) -> Fault {
        Fault { start, end, kind: FaultKind::Invalid, message: message.into() }
    }

    pub(crate) fn cannot(start: usize, end: usize, code: String, reason: &'static str) -> Fault {
        Fault { start, end, kind: FaultKind::Cannot { code, reason }, message: String::new() }
    }

    pub(crate) fn not_supported(
        start: usize,
        end: usize,
        code: impl Into<String>,
        note: &'static str,
    ) -> Fault {
        let code = code.into();
        Fault { start, end, kind: FaultKind::NotSupported { code, note }, message: String::new() }
    }
}

/// An input the interpreter can move about in: O-word loops and subroutine calls go back to
/// the byte offset of a line they passed ([`crate::interpret_seekable`]).
pub trait Seekable: BufRead {
    /// Moves so that the next byte read is the one at offset `to`; `from` is the offset of the
    /// next byte now (so that a buffered reader can keep its buffer for a short jump).
    fn jump(&mut self, from: u64, to: u64) -> io::Result<()>;

    /// Whether [`Seekable::jump`] works (false for a pipe or standard input: then the
    /// interpreter keeps the lines it may have to read again, within a bound).
    fn can_jump(&self) -> bool {
        true
    }
}

impl<F: Read + Seek> Seekable for BufReader<F> {
    fn jump(&mut self, from: u64, to: u64) -> io::Result<()> {
        let distance = i64::try_from(to).unwrap_or(i64::MAX) - i64::try_from(from).unwrap_or(0);
        self.seek_relative(distance)
    }
}

impl<T: AsRef<[u8]>> Seekable for io::Cursor<T> {
    fn jump(&mut self, _from: u64, to: u64) -> io::Result<()> {
        self.set_position(to);
        Ok(())
    }
}

impl<S: Seekable + ?Sized> Seekable for Box<S> {
    fn jump(&mut self, from: u64, to: u64) -> io::Result<()> {
        (**self).jump(from, to)
    }

    fn can_jump(&self) -> bool {
        (**self).can_jump()
    }
}

/// An input read only forwards (standard input, a pipe), as a [`Seekable`] that cannot jump.
#[derive(Debug)]
pub struct Forward<R>(pub R);

impl<R: BufRead> Read for Forward<R> {
    fn read(&mut self, out: &mut [u8]) -> io::Result<usize> {
        self.0.read(out)
    }
}

impl<R: BufRead> BufRead for Forward<R> {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        self.0.fill_buf()
    }

    fn consume(&mut self, amount: usize) {
        self.0.consume(amount);
    }
}

impl<R: BufRead> Seekable for Forward<R> {
    fn jump(&mut self, _from: u64, _to: u64) -> io::Result<()> {
        Err(io::Error::new(io::ErrorKind::Unsupported, "the input is read only forwards"))
    }

    fn can_jump(&self) -> bool {
        false
    }
}

/// How the interpreter moves in its main input: a [`Seekable`]'s jump, or none.
pub(crate) type JumpFn<R> = fn(&mut R, u64, u64) -> io::Result<()>;

/// Counts the bytes consumed from a reader (the offsets of lines, for jumps).
struct Counted<'a, B> {
    inner: &'a mut B,
    count: u64,
}

impl<B: BufRead> Read for Counted<'_, B> {
    fn read(&mut self, out: &mut [u8]) -> io::Result<usize> {
        let read = self.inner.read(out)?;
        self.count += read as u64;
        Ok(read)
    }
}

impl<B: BufRead> BufRead for Counted<'_, B> {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        self.inner.fill_buf()
    }

    fn consume(&mut self, amount: usize) {
        self.count += amount as u64;
        self.inner.consume(amount);
    }
}

/// The most bytes of lines a forwards-only input keeps to read them again (loop bodies and
/// subroutine definitions): 16 MiB.
pub(crate) const MAX_KEPT_BYTES: usize = 16 << 20;

/// A line of a forwards-only input kept to be read again.
#[derive(Debug)]
struct Kept {
    start: u64,
    next: u64,
    line: Box<[u8]>,
    too_long: bool,
    /// Kept for good (a subroutine definition), not only while a loop runs.
    keep: bool,
}

/// The lines of a forwards-only input (standard input, a pipe) that O-words may jump back to:
/// those of the loops being run and of the subroutines defined, within [`MAX_KEPT_BYTES`].
#[derive(Debug, Default)]
struct Tape {
    /// In input order.
    lines: Vec<Kept>,
    /// The kept line to read next instead of the input.
    replay: Option<usize>,
    /// Offset of the next byte of the input itself.
    live: u64,
    /// Whether lines read from the input are kept now (`Some(true)`: for good).
    recording: Option<bool>,
    bytes: usize,
    overflow: bool,
}

impl Tape {
    fn keep(&mut self, start: u64, next: u64, line: &[u8], too_long: bool, keep: bool) {
        if self.overflow {
            return;
        }
        if let Ok(index) = self.lines.binary_search_by_key(&start, |kept| kept.start) {
            self.lines[index].keep |= keep;
            return;
        }
        self.bytes += line.len() + std::mem::size_of::<Kept>();
        if self.bytes > MAX_KEPT_BYTES {
            self.overflow = true;
            self.lines = Vec::new();
            return;
        }
        self.lines.push(Kept { start, next, line: line.into(), too_long, keep });
    }
}

/// A file subroutine's input (as the [`crate::Environment`] opened it).
pub(crate) struct SubroutineFile(Box<dyn Seekable>);

impl std::fmt::Debug for SubroutineFile {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("SubroutineFile")
    }
}

/// Reads lines into one reused buffer, never holding more than `max + 1` bytes of a line
/// (`biscara_text::read_capped_line` with the dialect's cap).
#[derive(Debug)]
pub(crate) struct LineReader<R> {
    reader: Prefixed<R>,
    /// A file subroutine being read instead of the main input.
    file: Option<SubroutineFile>,
    /// Byte offset of the current line's start in the input being read (main or file).
    pub start: u64,
    /// Byte offset of the next line.
    pub next: u64,
    /// The main input's `next` while a file subroutine is read.
    main_next: u64,
    /// How to move in the main input (`None`: it is read only forwards).
    jump: Option<JumpFn<R>>,
    /// The lines kept of a main input read only forwards.
    tape: Tape,
    /// The current line (without `\n`, and without a `\r` before it), truncated to
    /// `max + 1` bytes.
    pub line: Vec<u8>,
    /// Whether the current line was longer than `max`.
    pub too_long: bool,
    /// 1-based number of the current line (0 before the first).
    pub number: usize,
    /// The longest line accepted, bytes: LinuxCNC's [`MAX_LINE`] unless a dialect says more.
    pub max: usize,
}

impl<R: BufRead> LineReader<R> {
    pub(crate) fn new(reader: R) -> LineReader<R> {
        LineReader {
            reader: Prefixed { head: Vec::new(), position: 0, inner: reader },
            file: None,
            start: 0,
            next: 0,
            main_next: 0,
            jump: None,
            tape: Tape::default(),
            line: Vec::with_capacity(MAX_LINE + 2),
            too_long: false,
            number: 0,
            max: MAX_LINE,
        }
    }

    /// The input, to read ahead in it before the first line.
    pub(crate) fn source(&mut self) -> &mut Prefixed<R> {
        &mut self.reader
    }

    /// Makes the main input one the reader can jump in.
    pub(crate) fn set_jump(&mut self, jump: JumpFn<R>) {
        self.jump = Some(jump);
    }

    /// Whether the main input says it can jump.
    pub(crate) fn source_can_jump(&self) -> bool
    where
        R: Seekable,
    {
        self.reader.inner.can_jump()
    }

    /// Whether the main input can be jumped in (file subroutines always can).
    pub(crate) fn can_jump(&self) -> bool {
        self.jump.is_some()
    }

    /// Whether a file subroutine is being read.
    pub(crate) fn in_file(&self) -> bool {
        self.file.is_some()
    }

    /// Reads `file` (a file subroutine, from its start) instead of the current input.
    pub(crate) fn open_file(&mut self, file: Box<dyn Seekable>) {
        if self.file.is_none() {
            self.main_next = self.next;
        }
        self.file = Some(SubroutineFile(file));
        self.next = 0;
    }

    /// Goes back to reading the main input where it was left.
    pub(crate) fn close_file(&mut self) {
        if self.file.take().is_some() {
            self.next = self.main_next;
        }
    }

    /// Moves to byte offset `to` of the input being read.
    pub(crate) fn seek(&mut self, to: u64) -> io::Result<()> {
        if to != self.next {
            match (&mut self.file, self.jump) {
                (Some(file), _) => file.0.jump(self.next, to)?,
                (None, Some(jump)) => self.reader.jump(jump, self.next, to)?,
                (None, None) => self.tape_seek(to)?,
            }
        }
        self.next = to;
        Ok(())
    }

    /// Whether lines are kept to be read again: a forwards-only main input being read.
    fn taping(&self) -> bool {
        self.file.is_none() && self.jump.is_none()
    }

    /// Keeps (`Some(keep)`) or stops keeping (`None`) the lines read from a forwards-only input
    /// from now on; the current line is kept too. Stopping forgets the lines not kept for good.
    pub(crate) fn set_recording(&mut self, recording: Option<bool>) {
        if !self.taping() {
            return;
        }
        self.tape.recording = recording;
        match recording {
            Some(keep) => {
                let line = std::mem::take(&mut self.line);
                self.tape.keep(self.start, self.next, &line, self.too_long, keep);
                self.line = line;
            }
            None => {
                self.tape.lines.retain(|kept| kept.keep);
                self.tape.bytes = self
                    .tape
                    .lines
                    .iter()
                    .map(|kept| kept.line.len() + std::mem::size_of::<Kept>())
                    .sum();
                let next = self.next;
                self.tape.replay = (next != self.tape.live)
                    .then(|| self.tape.lines.partition_point(|kept| kept.start < next));
            }
        }
    }

    /// Moves to offset `to` of a forwards-only input: a kept line, or where the input is.
    fn tape_seek(&mut self, to: u64) -> io::Result<()> {
        if self.tape.overflow {
            return Err(io::Error::other(format!(
                "more than {} MiB of loop bodies and subroutine definitions to keep",
                MAX_KEPT_BYTES >> 20
            )));
        }
        if to == self.tape.live {
            self.tape.replay = None;
            return Ok(());
        }
        match self.tape.lines.binary_search_by_key(&to, |kept| kept.start) {
            Ok(index) => {
                self.tape.replay = Some(index);
                Ok(())
            }
            Err(_) => Err(io::Error::new(io::ErrorKind::Unsupported, "that line was not kept")),
        }
    }

    /// A UTF-8 byte-order mark (Estlcam writes one) at the start of the first line is no
    /// character of the program.
    #[cold]
    #[inline(never)]
    fn skip_byte_order_mark(&mut self) {
        if self.line.starts_with(UTF8_BOM) {
            self.line.drain(..UTF8_BOM.len());
        }
    }

    /// The byte offset of the line after the current one.
    pub(crate) fn next_offset(&self) -> u64 {
        self.next
    }

    /// Reads the next line; `Ok(false)` at the end of the input.
    pub(crate) fn next_line(&mut self) -> io::Result<bool> {
        self.too_long = false;
        self.start = self.next;
        if let Some(index) = self.tape.replay {
            match self.tape.lines.get(index).filter(|kept| kept.start == self.next) {
                Some(kept) => {
                    self.line.clear();
                    self.line.extend_from_slice(&kept.line);
                    self.too_long = kept.too_long;
                    self.next = kept.next;
                    self.number += 1;
                    self.tape.replay = Some(index + 1);
                    return Ok(true);
                }
                None if self.next == self.tape.live => self.tape.replay = None,
                None => {
                    return Err(io::Error::other(
                        "a line to read again was not kept (the input is read only forwards)",
                    ));
                }
            }
        }
        let read = match &mut self.file {
            Some(file) => {
                let mut counted = Counted { inner: &mut file.0, count: 0 };
                let read = biscara_text::read_capped_line(&mut counted, &mut self.line, self.max);
                self.next += counted.count;
                read
            }
            None => {
                let mut counted = Counted { inner: &mut self.reader, count: 0 };
                let read = biscara_text::read_capped_line(&mut counted, &mut self.line, self.max);
                self.next += counted.count;
                read
            }
        };
        let read = read?;
        if self.taping() {
            self.tape.live = self.next;
            if let (Some(keep), Some(too_long)) = (self.tape.recording, read) {
                self.tape.keep(self.start, self.next, &self.line, too_long, keep);
            }
        }
        match read {
            Some(too_long) => {
                if self.start == 0 {
                    self.skip_byte_order_mark();
                }
                self.number += 1;
                self.too_long = too_long;
                Ok(true)
            }
            None => Ok(false),
        }
    }
}

/// An input with the bytes already read ahead from it (for `auto` dialect detection) put back
/// in front.
#[derive(Debug)]
pub(crate) struct Prefixed<R> {
    head: Vec<u8>,
    position: usize,
    inner: R,
}

impl<R: BufRead> Prefixed<R> {
    /// Reads up to `limit` bytes ahead (before anything was consumed); returns whether that
    /// is the whole input.
    pub(crate) fn read_ahead(&mut self, limit: usize) -> io::Result<bool> {
        while self.head.len() < limit {
            let available = match self.inner.fill_buf() {
                Ok(available) => available,
                Err(err) if err.kind() == io::ErrorKind::Interrupted => continue,
                Err(err) => return Err(err),
            };
            if available.is_empty() {
                return Ok(true);
            }
            let take = available.len().min(limit - self.head.len());
            self.head.extend_from_slice(&available[..take]);
            self.inner.consume(take);
        }
        Ok(false)
    }

    /// The bytes read ahead.
    pub(crate) fn head(&self) -> &[u8] {
        &self.head
    }

    /// Moves to offset `to` with `jump`; `from` is the offset of the next byte.
    fn jump(&mut self, jump: JumpFn<R>, from: u64, to: u64) -> io::Result<()> {
        let from = if self.head.is_empty() {
            from
        } else {
            // The inner reader is past the bytes read ahead.
            let inner = self.head.len() as u64;
            self.head = Vec::new();
            self.position = 0;
            inner
        };
        jump(&mut self.inner, from, to)
    }
}

impl<R: BufRead> io::Read for Prefixed<R> {
    fn read(&mut self, out: &mut [u8]) -> io::Result<usize> {
        let available = self.fill_buf()?;
        let count = available.len().min(out.len());
        out[..count].copy_from_slice(&available[..count]);
        self.consume(count);
        Ok(count)
    }
}

impl<R: BufRead> BufRead for Prefixed<R> {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        if self.position < self.head.len() {
            return Ok(&self.head[self.position..]);
        }
        self.inner.fill_buf()
    }

    fn consume(&mut self, amount: usize) {
        if self.position < self.head.len() {
            self.position += amount;
            if self.position >= self.head.len() {
                // Read ahead once: give the memory back.
                self.head = Vec::new();
                self.position = 0;
            }
        } else {
            self.inner.consume(amount);
        }
    }
}

/// Slots of [`Compact`]'s arrays: more than [`MAX_LINE`], to tell a line that has more.
const COMPACT_SLOTS: usize = MAX_LINE + 4;

/// The significant characters of one line (at most [`MAX_LINE`] of them: fixed arrays, no
/// allocation, no capacity checks).
#[derive(Debug)]
pub(crate) struct Compact {
    bytes: [u8; COMPACT_SLOTS],
    /// For each byte of `bytes`, its 0-based byte offset in the raw line (< 65 536).
    columns: [u16; COMPACT_SLOTS],
    len: usize,
}

impl Default for Compact {
    fn default() -> Compact {
        Compact { bytes: [0; COMPACT_SLOTS], columns: [0; COMPACT_SLOTS], len: 0 }
    }
}

impl Compact {
    /// Lower-case characters outside comments, without spaces and tabs; a comment is one `(`.
    pub(crate) fn bytes(&self) -> &[u8] {
        &self.bytes[..self.len]
    }

    /// Mutable significant characters (a dialect renames a word's letter).
    pub(crate) fn bytes_mut(&mut self) -> &mut [u8] {
        &mut self.bytes[..self.len]
    }

    /// Stores `byte`, from raw offset `column`, in slot `*len` and moves `len` on; drops it when
    /// the slots are full (the line is then refused).
    #[inline(always)]
    fn keep(&mut self, len: &mut usize, byte: u8, column: usize) {
        if *len < COMPACT_SLOTS {
            self.bytes[*len] = byte;
            self.columns[*len] = column.min(usize::from(u16::MAX)) as u16;
            *len += 1;
        }
    }

    /// Takes compact indices `range` out of the line (a dialect's word read before the block
    /// reader), the columns of the rest kept.
    pub(crate) fn remove(&mut self, range: std::ops::Range<usize>) {
        let (start, end) = (range.start.min(self.len), range.end.min(self.len));
        self.bytes.copy_within(end..self.len, start);
        self.columns.copy_within(end..self.len, start);
        self.len -= end - start;
    }

    /// Replaces compact indices `range` by `text` (a dialect's line rewritten in LinuxCNC's
    /// words), each new byte at the column of the range's start; `false` (nothing changed) when
    /// the line would get too long.
    pub(crate) fn replace(&mut self, range: std::ops::Range<usize>, text: &[u8]) -> bool {
        let (start, end) = (range.start.min(self.len), range.end.min(self.len));
        let len = self.len - (end - start) + text.len();
        if len > MAX_LINE {
            return false;
        }
        let column = if self.len == 0 { 0 } else { self.columns[start.min(self.len - 1)] };
        self.bytes.copy_within(end..self.len, start + text.len());
        self.columns.copy_within(end..self.len, start + text.len());
        self.bytes[start..start + text.len()].copy_from_slice(text);
        self.columns[start..start + text.len()].fill(column);
        self.len = len;
        true
    }

    /// The raw offset of compact index `index` (the line's end for `index >= len`).
    pub(crate) fn column(&self, index: usize, raw_len: usize) -> usize {
        if index < self.len { usize::from(self.columns[index]) } else { raw_len }
    }
}

/// LinuxCNC's error for a `(` comment with no `)` on its line.
pub(crate) const UNCLOSED_COMMENT: &str = "Unclosed comment found";

/// What a `(` inside a `( )` comment is, by dialect.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum InnerParen {
    /// LinuxCNC's "Nested comment found".
    Refused,
    /// A comment within the comment, closed by its own `)` (Mach3, Marlin).
    Opens,
    /// A character of the comment, which the first `)` ends (Grbl's protocol.c: "ignore all
    /// characters until ')' or EOL").
    Ignored,
}

/// Fills `out` with the significant characters of `raw` (LinuxCNC's `close_and_downcase`), a
/// `(` inside a comment read as `inner` says. A line longer than [`MAX_LINE`] (a dialect's long
/// comment) is refused if more than [`MAX_LINE`] significant characters remain.
// Not inlined into the interpreter's loop, whose registers are all taken: its own function
// keeps the loop's pointers and counters in registers.
#[inline(never)]
pub(crate) fn compact(raw: &[u8], out: &mut Compact, inner: InnerParen) -> Result<(), Fault> {
    // Every line passes here: one table look-up tells an ordinary character (kept, lower
    // case) from the four that are not, the length is kept in a local, and a comment is
    // skipped by its own loop. Characters beyond the slots (a long line's: it is refused below)
    // are dropped.
    out.len = 0;
    let mut len = 0;
    let mut chars = raw.iter().enumerate();
    while let Some((index, &byte)) = chars.next() {
        let lowered = LOWERED[usize::from(byte)];
        let kept = if lowered <= u16::from(u8::MAX) {
            lowered as u8
        } else {
            match byte {
                b'(' => {
                    if let Err(fault) = skip_comment(&mut chars, raw.len(), index, inner) {
                        // The line as far as it was read, for a dialect that ends an unclosed
                        // comment at the end of its line (Grbl).
                        out.keep(&mut len, b'(', index);
                        out.len = len;
                        return Err(fault);
                    }
                    b'('
                }
                // LinuxCNC keeps the `;` (a value cannot be read from it); the rest is comment.
                b';' => {
                    out.keep(&mut len, b';', index);
                    break;
                }
                _ => continue,
            }
        };
        out.keep(&mut len, kept, index);
    }
    out.len = len;
    if out.len > MAX_LINE {
        let start = out.column(MAX_LINE, raw.len());
        return Err(Fault::syntax(
            start,
            raw.len(),
            format!(
                "Command too long: more than {MAX_LINE} characters outside comments (the \
                 dialect accepts long comment lines, not long commands)"
            ),
        ));
    }
    Ok(())
}

/// Each byte lower-cased, or above `u8::MAX` for the four that are not kept as they are:
/// space, tab, `(` and `;`.
const LOWERED: [u16; 256] = {
    let mut table = [0; 256];
    let mut byte = 0;
    while byte < 256 {
        table[byte] = match byte as u8 {
            b' ' | b'\t' | b'(' | b';' => 0x100,
            other => other.to_ascii_lowercase() as u16,
        };
        byte += 1;
    }
    table
};

/// Moves `chars` past the `)` that closes the comment opened at `open`.
fn skip_comment(
    chars: &mut std::iter::Enumerate<std::slice::Iter<'_, u8>>,
    raw_len: usize,
    open: usize,
    inner: InnerParen,
) -> Result<(), Fault> {
    let mut depth = 1usize;
    for (index, &byte) in chars {
        match byte {
            b')' if depth > 1 => depth -= 1,
            b')' => return Ok(()),
            b'(' => match inner {
                InnerParen::Opens => depth += 1,
                InnerParen::Ignored => {}
                InnerParen::Refused => {
                    return Err(Fault::syntax(open, index + 1, "Nested comment found"));
                }
            },
            _ => {}
        }
    }
    Err(Fault::syntax(open, raw_len, UNCLOSED_COMMENT))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn squeeze(raw: &str) -> Result<(String, Vec<u32>), String> {
        let mut out = Compact::default();
        compact(raw.as_bytes(), &mut out, InnerParen::Refused).map_err(|fault| fault.message)?;
        let columns = (0..out.bytes().len()).map(|i| out.column(i, raw.len()) as u32).collect();
        Ok((String::from_utf8(out.bytes().to_vec()).unwrap(), columns))
    }

    #[test]
    fn spaces_go_case_folds_comments_shrink() {
        let (text, columns) = squeeze("G0 X1 (move) y 2.5 ; rest").unwrap();
        assert_eq!(text, "g0x1(y2.5;");
        assert_eq!(columns, [0, 1, 3, 4, 6, 13, 15, 16, 17, 19]);
        assert_eq!(squeeze("G0 (a(b))").unwrap_err(), "Nested comment found");
        assert_eq!(squeeze("G0 (open").unwrap_err(), "Unclosed comment found");
    }

    #[test]
    fn nested_comments_close_at_their_own_parenthesis() {
        let mut out = Compact::default();
        compact(b"G0 (a (b) c) X1", &mut out, InnerParen::Opens).unwrap();
        assert_eq!(out.bytes(), b"g0(x1");
        assert_eq!(out.column(3, 15), 13);
        let fault = compact(b"G0 (a (b) c", &mut out, InnerParen::Opens).unwrap_err();
        assert_eq!(fault.message, "Unclosed comment found");
        // Grbl: the first `)` ends the comment, an inner `(` is one of its characters.
        compact(b"G0 (a (b) X1", &mut out, InnerParen::Ignored).unwrap();
        assert_eq!(out.bytes(), b"g0(x1");
        let fault = compact(b"G0 (a (b) c) X1", &mut out, InnerParen::Refused).unwrap_err();
        assert_eq!(fault.message, "Nested comment found");
    }

    #[test]
    fn long_lines_keep_columns_and_refuse_long_commands() {
        let mut out = Compact::default();
        let long = format!("({}) G1 X1", "c".repeat(1000));
        compact(long.as_bytes(), &mut out, InnerParen::Refused).unwrap();
        assert_eq!(out.bytes(), b"(g1x1");
        assert_eq!(out.column(1, long.len()), 1003);
        let command = format!("G1 X{}", "1".repeat(400));
        let fault = compact(command.as_bytes(), &mut out, InnerParen::Refused).unwrap_err();
        assert!(fault.message.starts_with("Command too long"), "{}", fault.message);
    }

    #[test]
    fn read_ahead_bytes_are_read_again() {
        let mut reader = LineReader::new("first\nsecond\nthird".as_bytes());
        assert!(!reader.source().read_ahead(8).unwrap());
        assert_eq!(reader.source().head(), b"first\nse");
        let mut seen = Vec::new();
        while reader.next_line().unwrap() {
            seen.push(String::from_utf8(reader.line.clone()).unwrap());
        }
        assert_eq!(seen, ["first", "second", "third"]);
        let mut whole = LineReader::new("a\n".as_bytes());
        assert!(whole.source().read_ahead(64).unwrap());
    }

    #[test]
    fn lines_are_read_without_endings_and_capped() {
        let text = format!("a\r\nb\n{}\nlast", "x".repeat(1000));
        let mut reader = LineReader::new(text.as_bytes());
        let mut seen = Vec::new();
        while reader.next_line().unwrap() {
            seen.push((reader.number, reader.line.len(), reader.too_long));
        }
        assert_eq!(seen, [(1, 1, false), (2, 1, false), (3, MAX_LINE + 1, true), (4, 4, false)]);
    }
}
