//! Reading STL meshes (binary and ASCII), streaming, for the viewer's optional link meshes.
//!
//! Written here rather than taken from a crate: the viewer needs only the triangles' corners
//! (normals are recomputed by the page), a bound on memory enforced while reading (a file with
//! more triangles than the page takes is refused before its triangles are held), and errors that
//! say where the file is wrong (`LINE:COL:` for ASCII, `byte N:` for binary), which the readers
//! at hand do not give.

use std::io::{self, BufRead, Read};

use biscara_text::{LineError, LineReader, Located};

/// Most triangles the viewer takes, all meshes together (each is 48 bytes of the page: a
/// 200 000-triangle robot adds about 10 MB). Larger meshes are refused, not thinned: simplify
/// them in the CAD program or a mesh tool (MeshLab's or Blender's decimation) first.
pub const MAX_MESH_TRIANGLES: usize = 200_000;

/// The triangles of an STL file, in the file's units.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StlMesh {
    /// Nine numbers per triangle: its three corners' x, y, z.
    positions: Vec<f32>,
}

impl StlMesh {
    /// The number of triangles.
    pub fn triangles(&self) -> usize {
        self.positions.len() / 9
    }

    /// A mesh of the given corners (nine numbers per triangle; a trailing partial triangle is
    /// dropped).
    pub fn from_positions(mut positions: Vec<f32>) -> StlMesh {
        positions.truncate(positions.len() / 9 * 9);
        StlMesh { positions }
    }

    /// The corners, nine numbers per triangle (x, y, z of each corner), in the file's units.
    pub fn positions(&self) -> &[f32] {
        &self.positions
    }
}

/// Why an STL file cannot be used. Messages start with `LINE:COL: ` (ASCII) or `byte N: `
/// (binary), so a caller only prefixes the file name.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StlError {
    /// Occurs when the file cannot be read, or an ASCII line is not text or too long.
    #[error(transparent)]
    Read(#[from] Located<LineError>),
    /// Occurs when an ASCII STL is not written as `solid … facet normal … outer loop vertex …
    /// endloop endfacet … endsolid`, a vertex is not a finite number, or it holds too many
    /// triangles.
    #[error("{0}")]
    Ascii(Located<String>),
    /// Occurs when a binary STL is shorter or longer than its header's triangle count says, a
    /// vertex is not a finite number, it holds too many triangles, or the file is no STL at all.
    #[error("byte {byte}: {fault}")]
    Binary {
        /// 0-based offset in the file.
        byte: u64,
        /// What is wrong there.
        fault: BinaryFault,
    },
}

/// What is wrong at a byte of a binary STL ([`StlError::Binary`]).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum BinaryFault {
    /// Occurs when the file cannot be read.
    #[error("cannot read the STL file: {0}")]
    Io(io::Error),
    /// Occurs when the file is shorter than a binary STL's header.
    #[error(
        "not an STL file: a binary STL begins with an 84-byte header, this file has {bytes} bytes"
    )]
    ShortHeader {
        /// The file's length.
        bytes: usize,
    },
    /// Occurs when the header's triangle count is zero.
    #[error("the header announces no triangles")]
    NoTriangles,
    /// Occurs when the header announces more triangles than the caller takes.
    #[error("the header announces {count} triangles: {}", too_many(*.max))]
    TooManyTriangles {
        /// The header's count.
        count: usize,
        /// The most taken.
        max: usize,
    },
    /// Occurs when the file ends before the triangles its header announces.
    #[error(
        "the file ends inside triangle {triangle} of the {count} its header announces \
         (truncated, or a wrong triangle count)"
    )]
    Truncated {
        /// The triangle cut short, from 1.
        triangle: usize,
        /// The header's count.
        count: usize,
    },
    /// Occurs when a vertex coordinate is infinite or not a number.
    #[error("triangle {triangle}, corner {corner}: {axis} = {value} is not a finite number")]
    NotFinite {
        /// The triangle, from 1.
        triangle: usize,
        /// The corner, 1 to 3.
        corner: usize,
        /// The coordinate: `x`, `y` or `z`.
        axis: &'static str,
        /// What the file holds.
        value: f32,
    },
    /// Occurs when bytes follow the triangles the header announces.
    #[error(
        "the header announces {count} triangles, but more bytes follow (a wrong triangle \
         count, or not an STL file)"
    )]
    TrailingBytes {
        /// The header's count.
        count: usize,
    },
}

/// Reads an STL file, binary or ASCII (told apart by the first 84 bytes: an ASCII file is text
/// beginning with `solid`; a binary header's triangle count holds a zero byte below 16 million
/// triangles), keeping at most `max_triangles` triangles.
///
/// ```
/// let ascii = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
///              vertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
/// let mesh = biscara_view::read_stl(ascii.as_bytes(), 10)?;
/// assert_eq!(mesh.triangles(), 1);
/// assert_eq!(mesh.positions()[3], 1.0);
/// # Ok::<(), biscara_view::StlError>(())
/// ```
pub fn read_stl(mut input: impl BufRead, max_triangles: usize) -> Result<StlMesh, StlError> {
    let mut header = Vec::with_capacity(84);
    (&mut input).take(84).read_to_end(&mut header).map_err(|err| binary_io(0, err))?;
    // Text: UTF-8 (a character cut by the 84th byte allowed), no control bytes but whitespace.
    let utf8 = std::str::from_utf8(&header).map_or_else(|err| err.error_len().is_none(), |_| true);
    let text = utf8
        && header.iter().all(|&b| b >= 0x20 && b != 0x7f || matches!(b, b'\t' | b'\n' | b'\r'));
    let starts_solid =
        header.trim_ascii_start().get(..5).is_some_and(|w| w.eq_ignore_ascii_case(b"solid"));
    if text && starts_solid {
        return read_ascii(io::Cursor::new(header).chain(input), max_triangles);
    }
    if text && !header.is_empty() {
        let message = "not an STL file: text that does not begin with `solid`".to_owned();
        return Err(StlError::Ascii(Located::at(1, 1, message)));
    }
    if header.len() < 84 {
        return Err(binary(header.len() as u64, BinaryFault::ShortHeader { bytes: header.len() }));
    }
    read_binary(&header, input, max_triangles)
}

fn binary(byte: u64, fault: BinaryFault) -> StlError {
    StlError::Binary { byte, fault }
}

fn binary_io(byte: u64, err: io::Error) -> StlError {
    binary(byte, BinaryFault::Io(err))
}

fn too_many(max_triangles: usize) -> String {
    format!(
        "more than {max_triangles} triangles, what the viewer takes: simplify the mesh first \
         (a CAD program's export resolution, or a mesh tool's decimation)"
    )
}

fn read_binary(header: &[u8], mut input: impl BufRead, max: usize) -> Result<StlMesh, StlError> {
    let count = u32::from_le_bytes([header[80], header[81], header[82], header[83]]) as usize;
    if count == 0 {
        return Err(binary(80, BinaryFault::NoTriangles));
    }
    if count > max {
        return Err(binary(80, BinaryFault::TooManyTriangles { count, max }));
    }
    let mut positions = Vec::with_capacity(count * 9);
    let mut record = [0u8; 50];
    for index in 0..count {
        let start = 84 + 50 * index as u64;
        if let Err(err) = input.read_exact(&mut record) {
            return Err(if err.kind() == io::ErrorKind::UnexpectedEof {
                binary(start, BinaryFault::Truncated { triangle: index + 1, count })
            } else {
                binary_io(start, err)
            });
        }
        // The normal (bytes 0..12) is recomputed by the page; the attribute bytes are unused.
        for corner in 0..3 {
            for axis in 0..3 {
                let at = 12 + 12 * corner + 4 * axis;
                let value = f32::from_le_bytes([
                    record[at],
                    record[at + 1],
                    record[at + 2],
                    record[at + 3],
                ]);
                if !value.is_finite() {
                    return Err(binary(
                        start + at as u64,
                        BinaryFault::NotFinite {
                            triangle: index + 1,
                            corner: corner + 1,
                            axis: ["x", "y", "z"][axis],
                            value,
                        },
                    ));
                }
                positions.push(value);
            }
        }
    }
    let end = 84 + 50 * count as u64;
    let more = input.fill_buf().map_err(|err| binary_io(end, err))?;
    if !more.is_empty() {
        return Err(binary(end, BinaryFault::TrailingBytes { count }));
    }
    Ok(StlMesh { positions })
}

/// The words of an ASCII STL, each with its line and column.
struct Words<R> {
    lines: LineReader<R>,
    /// The current line's words not taken yet (reversed), with their columns.
    pending: Vec<(usize, String)>,
    line: usize,
    /// Where the last word ended (for an error at the end of the file).
    end: (usize, usize),
}

impl<R: BufRead> Words<R> {
    fn next(&mut self) -> Result<Option<(usize, usize, String)>, StlError> {
        loop {
            if let Some((column, word)) = self.pending.pop() {
                self.end = (self.line, column + word.len());
                return Ok(Some((self.line, column, word)));
            }
            match self.lines.next_line() {
                Ok(Some((line, text))) => {
                    self.line = line;
                    let mut words = Vec::new();
                    let mut start = None;
                    for (index, ch) in text.char_indices().chain([(text.len(), ' ')]) {
                        match (ch.is_whitespace(), start) {
                            (false, None) => start = Some(index),
                            (true, Some(from)) => {
                                let column = text[..from].chars().count() + 1;
                                words.push((column, text[from..index].to_owned()));
                                start = None;
                            }
                            _ => {}
                        }
                    }
                    words.reverse();
                    self.pending = words;
                }
                Ok(None) => return Ok(None),
                Err(err) => return Err(err.into()),
            }
        }
    }

    /// Drops the rest of the current line (a solid's name).
    fn skip_line(&mut self) {
        self.pending.clear();
    }

    fn error(&self, line: usize, column: usize, message: String) -> StlError {
        StlError::Ascii(Located::at(line, column, message))
    }

    /// The next word, which must be `keyword` (any case).
    fn expect(&mut self, keyword: &str) -> Result<(), StlError> {
        match self.next()? {
            Some((_, _, word)) if word.eq_ignore_ascii_case(keyword) => Ok(()),
            Some((line, column, word)) => {
                Err(self.error(line, column, format!("expected `{keyword}`, found `{word}`")))
            }
            None => {
                let (line, column) = self.end;
                Err(self.error(line, column, format!("the file ends where `{keyword}` should be")))
            }
        }
    }

    /// The next word as a number; `what` names it in errors; `finite` requires a finite one.
    fn number(&mut self, what: &str, finite: bool) -> Result<f32, StlError> {
        match self.next()? {
            Some((line, column, word)) => match word.parse::<f32>() {
                Ok(value) if !finite || value.is_finite() => Ok(value),
                Ok(value) => Err(self.error(
                    line,
                    column,
                    format!("{what} = {value} is not a finite number"),
                )),
                Err(_) => Err(self.error(line, column, format!("expected {what}, found `{word}`"))),
            },
            None => {
                let (line, column) = self.end;
                Err(self.error(line, column, format!("the file ends where {what} should be")))
            }
        }
    }
}

fn read_ascii(input: impl BufRead, max: usize) -> Result<StlMesh, StlError> {
    let mut words =
        Words { lines: LineReader::new(input), pending: Vec::new(), line: 0, end: (1, 1) };
    let mut positions = Vec::new();
    // One or more solids, each `solid NAME` … `endsolid NAME`.
    let mut solids = 0;
    loop {
        match words.next()? {
            None if solids > 0 => break,
            Some((_, _, word)) if word.eq_ignore_ascii_case("solid") => words.skip_line(),
            Some((line, column, word)) => {
                return Err(words.error(line, column, format!("expected `solid`, found `{word}`")));
            }
            None => {
                let (line, column) = words.end;
                return Err(words.error(line, column, "the file holds no solid".to_owned()));
            }
        }
        solids += 1;
        loop {
            let Some((line, column, word)) = words.next()? else {
                let (line, column) = words.end;
                return Err(words.error(
                    line,
                    column,
                    "the file ends before `endsolid`".to_owned(),
                ));
            };
            if word.eq_ignore_ascii_case("endsolid") {
                words.skip_line();
                break;
            }
            if !word.eq_ignore_ascii_case("facet") {
                return Err(words.error(
                    line,
                    column,
                    format!("expected `facet` or `endsolid`, found `{word}`"),
                ));
            }
            if positions.len() / 9 >= max {
                return Err(words.error(line, column, too_many(max)));
            }
            words.expect("normal")?;
            for axis in ["the normal's x", "the normal's y", "the normal's z"] {
                words.number(axis, false)?;
            }
            words.expect("outer")?;
            words.expect("loop")?;
            for _ in 0..3 {
                words.expect("vertex")?;
                for axis in ["the vertex's x", "the vertex's y", "the vertex's z"] {
                    positions.push(words.number(axis, true)?);
                }
            }
            words.expect("endloop")?;
            words.expect("endfacet")?;
        }
    }
    if positions.is_empty() {
        let (line, column) = words.end;
        return Err(words.error(line, column, "the file holds no triangles".to_owned()));
    }
    Ok(StlMesh { positions })
}

#[cfg(test)]
mod tests {
    use super::*;

    const TRIANGLE: &str = "solid tri\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      \
                            vertex 10 0 0\n      vertex 0 5.5 -1e1\n    endloop\n  endfacet\nendsolid tri\n";

    /// A binary STL of `triangles` (each three corners), with `header` as its first bytes.
    fn binary_stl(header: &[u8], triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
        let mut bytes = vec![b' '; 80];
        bytes[..header.len()].copy_from_slice(header);
        bytes.extend((triangles.len() as u32).to_le_bytes());
        for triangle in triangles {
            bytes.extend([0u8; 12]);
            for value in triangle.iter().flatten() {
                bytes.extend(value.to_le_bytes());
            }
            bytes.extend([0u8; 2]);
        }
        bytes
    }

    #[track_caller]
    fn check_error(bytes: &[u8], expected: &str) {
        let err = read_stl(bytes, 1000).expect_err("must be refused");
        assert!(err.to_string().starts_with(expected), "{err} lacks {expected:?}");
    }

    #[test]
    fn ascii_triangles_are_read_with_several_solids_and_any_case() {
        let mesh = read_stl(TRIANGLE.as_bytes(), 10).unwrap();
        assert_eq!(mesh.positions(), [0.0, 0.0, 0.0, 10.0, 0.0, 0.0, 0.0, 5.5, -10.0]);
        let two = format!("{TRIANGLE}{}", TRIANGLE.to_uppercase().replace("SOLID TRI", "SOLID"));
        assert_eq!(read_stl(two.as_bytes(), 10).unwrap().triangles(), 2);
        // CRLF line ends, a NaN normal (unused) and a name with spaces.
        let crlf = TRIANGLE.replace('\n', "\r\n").replace("normal 0 0 1", "normal nan nan nan");
        let crlf = crlf.replace("solid tri", "solid my part v2");
        assert_eq!(read_stl(crlf.as_bytes(), 10).unwrap().triangles(), 1);
    }

    #[test]
    fn binary_triangles_are_read_even_with_a_header_saying_solid() {
        let corners = [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 9.5]];
        let bytes = binary_stl(b"solid exported by a CAD program", &[corners, corners]);
        let mesh = read_stl(&bytes[..], 10).unwrap();
        assert_eq!(mesh.triangles(), 2);
        assert_eq!(&mesh.positions()[..9], [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.5]);
    }

    #[test]
    fn bad_binary_files_are_refused_with_the_byte() {
        let corners = [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 9.0]];
        let good = binary_stl(b"", &[corners, corners]);
        // Truncated in the second triangle.
        check_error(&good[..good.len() - 10], "byte 134: the file ends inside triangle 2 of the 2");
        // A count larger or smaller than the triangles that follow.
        let mut wrong = good.clone();
        wrong[80] = 3;
        check_error(&wrong, "byte 184: the file ends inside triangle 3 of the 3");
        wrong[80] = 1;
        check_error(&wrong, "byte 134: the header announces 1 triangles, but more bytes follow");
        wrong[80] = 0;
        check_error(&wrong, "byte 80: the header announces no triangles");
        // A NaN corner.
        let nan = binary_stl(b"", &[[[1.0, 2.0, 3.0], [4.0, f32::NAN, 6.0], [7.0, 8.0, 9.0]]]);
        check_error(&nan, "byte 112: triangle 1, corner 2: y = NaN is not a finite number");
        // More triangles than the page takes: refused from the header.
        let err = read_stl(&good[..], 1).unwrap_err();
        assert!(
            err.to_string().starts_with("byte 80: the header announces 2 triangles: more than 1"),
            "{err}"
        );
        // Not STL at all: short binary bytes, an empty file, a PNG's first bytes.
        check_error(b"\x89PNG\r\n\x1a\n", "byte 8: not an STL file");
        check_error(b"", "byte 0: not an STL file");
    }

    #[test]
    fn bad_ascii_files_are_refused_with_line_and_column() {
        let check = |text: &str, expected: &str| check_error(text.as_bytes(), expected);
        check("{\"robot\": 1}", "1:1: not an STL file: text that does not begin with `solid`");
        check(
            &TRIANGLE.replace("vertex 10 0 0", "vertex 10 nan 0"),
            "5:17: the vertex's y = NaN is not",
        );
        check(
            &TRIANGLE.replace("vertex 10 0 0", "vertex 10 0"),
            "6:7: expected the vertex's z, found `vertex`",
        );
        check(&TRIANGLE.replace("outer loop", "outer lop"), "3:11: expected `loop`, found `lop`");
        check(
            &TRIANGLE.replace("vertex 0 5.5 -1e1\n", ""),
            "6:11: expected `vertex`, found `endloop`",
        );
        // Truncated: no endsolid; no triangles; cut inside a facet.
        check(&TRIANGLE.replace("endsolid tri\n", ""), "8:11: the file ends before `endsolid`");
        check("solid empty\nendsolid empty\n", "2:9: the file holds no triangles");
        check(&TRIANGLE[..60], "4:15: the file ends where the vertex's y should be");
        check(
            &TRIANGLE.replace("endfacet", "endfacet\nfacet 1 2 3"),
            "9:7: expected `normal`, found `1`",
        );
        // Too many triangles for the page: stopped at the facet past the bound.
        let two = format!("solid a\n{0}{0}endsolid a\n", &TRIANGLE[10..TRIANGLE.len() - 13]);
        let err = read_stl(two.as_bytes(), 1).unwrap_err();
        assert!(err.to_string().starts_with("9:3: more than 1 triangles"), "{err}");
    }
}
