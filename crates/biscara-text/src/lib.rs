//! The text plumbing every biscara stage shares, so that each reads and writes text the same way:
//!
//! - bounded lines: [`read_capped_line`] (bytes, the cap a parameter: the G-code lexer's 252),
//!   and on it [`LineReader`] (1-based lines, UTF-8 and NUL checked, at most
//!   [`MAX_LINE_BYTES`]) and [`read_bounded_line`] (the same bound, `io::Error`s);
//! - fixed-decimal numbers: [`fixed()`] (never a negative zero), [`round_to`] for JSON, and the
//!   [`RowBuffer`] the CSV writers gather rows in, with its fast formatter;
//! - rows of numbers: [`NumericCsvReader`], the reader under the path and joint CSVs;
//! - the readers' error shape: [`Located`] (line, column, span, and a kind per reader);
//! - the readers' iterator: [`RecordReader`] (records until the end or the first error);
//! - message helpers: [`shorten`], [`compact`], [`strip_position`];
//! - values a user types (a command line's flags): [`number_in`], [`parse_xyzc`], [`parse_sizes`]
//!   and the others of [`ValueError`]'s variants.
//!
//! It knows no file format of its own (no header, no column meaning) and nothing of robots,
//! G-code or CL: those live in the stage crates on top of it. It never prints and never opens a
//! file.
//!
//! ```
//! use biscara_text::{LineReader, RowBuffer, fixed};
//!
//! let mut lines = LineReader::new("GOTO/1,2,3\r\nFINI\n".as_bytes());
//! assert_eq!(lines.next_line().unwrap(), Some((1, "GOTO/1,2,3")));
//! assert_eq!(fixed(-0.0001, 3), "0.000");
//! let mut row = RowBuffer::new();
//! row.push_fixed_list([0.5, -2.0], 3);
//! assert_eq!(row.as_bytes(), b"0.500,-2.000");
//! ```

mod csv;
mod fixed;
mod lines;
mod located;
mod message;
mod records;
mod values;

pub use csv::{CsvError, CsvErrorKind, MAX_CSV_COLUMNS, NumericCsvReader};
pub use fixed::{FLUSH_AT, MAX_DECIMALS, RowBuffer, fixed, push_fixed, round_to};
pub use lines::{LineError, LineReader, MAX_LINE_BYTES, read_bounded_line, read_capped_line};
pub use located::Located;
pub use message::{compact, shorten, strip_position};
pub use records::RecordReader;
pub use values::{
    ValueError, non_negative, number_in, numbers, parse_seconds, parse_sizes, parse_xy, parse_xyzc,
};
