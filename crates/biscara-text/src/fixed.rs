//! Fixed-decimal numbers: [`fixed`] for text written a number at a time, [`round_to`] for JSON
//! outputs, and the [`RowBuffer`] the CSV writers gather their rows in, with its fast formatter.
//!
//! The fast formatter is the CSV writers' hot spot: 40 % of the instructions of `joints` with the
//! first, digit-at-a-time writer, and still a fifth of its time after. A number is scaled to an
//! integer whose digits are made eight at a time, without a loop, and stored straight into the
//! row buffer; its length is counted from the integer, not from the digits. Values too large to
//! scale exactly fall back to [`fixed`].
//!
//! What each step bought, in time (`joints` on the 200,000-line engraving program of
//! `scripts/gen-program.sh`, median of 10 interleaved runs): digits two at a time into a stack
//! array, then appended to a `Vec`, was the baseline; eight at a time straight into the buffer
//! changed nothing by itself (0.56 s either way: fewer branches, more multiplications on one
//! dependency chain); counting the integer digits on the scaled integer, so that where the next
//! number goes no longer waits for this one's digits, took 0.475 s to 0.444 s. Counted in
//! instructions (`valgrind --tool=callgrind`, `joints` on the 20,000-line engraving program), a
//! number then cost 125.6 with the row's loop; made and stored from one 64-bit register when it
//! is below 10⁸ once scaled, inline in the row's loop over room made once per row: 90.7.

use std::io::{self, Write};

/// The largest number of decimals [`push_fixed`] and [`RowBuffer::push_fixed`] write.
pub const MAX_DECIMALS: usize = 12;

/// Rows are gathered in the writer's own buffer and handed to the output in chunks of about this
/// many bytes: one copy per byte instead of two (row buffer, then `BufWriter`).
pub const FLUSH_AT: usize = 1 << 16;

/// Room past [`FLUSH_AT`] for the row that crosses it (longer rows grow the buffer).
const ROW_ROOM: usize = 1024;

/// The bytes the fast path may write to: a sign, 16 integer digits (|scaled| < 4e15), a point
/// and a 16-byte store of the fraction, of which at most [`MAX_DECIMALS`] bytes are kept.
const FAST_WIDTH: usize = 34;

/// Scaled values at or beyond this take the `format!` path (below it the scaled value and its
/// rounding are exact in `i64`, and the text fits in [`FAST_WIDTH`] bytes).
const FAST_LIMIT: f64 = 4.0e15;

const POWERS_OF_TEN: [f64; MAX_DECIMALS + 1] =
    [1.0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12];

/// Powers of ten as integers, for counting the digits of a scaled value.
const INTEGER_POWERS_OF_TEN: [u64; 16] = [
    1,
    10,
    100,
    1_000,
    10_000,
    100_000,
    1_000_000,
    10_000_000,
    100_000_000,
    1_000_000_000,
    10_000_000_000,
    100_000_000_000,
    1_000_000_000_000,
    10_000_000_000_000,
    100_000_000_000_000,
    1_000_000_000_000_000,
];

/// CSV text gathered before it is handed to the output: bytes are written in place, without a
/// `Vec` length and capacity check per byte, and a number goes straight into the buffer rather
/// than through a stack array.
#[derive(Debug, Clone)]
pub struct RowBuffer {
    /// Text, then scratch: numbers are written whole into the bytes past `len`, which grow when
    /// fewer than [`FAST_WIDTH`] (or a long number) are left.
    bytes: Vec<u8>,
    /// Bytes written.
    len: usize,
}

impl Default for RowBuffer {
    fn default() -> Self {
        RowBuffer::new()
    }
}

impl RowBuffer {
    /// An empty buffer, with room for [`FLUSH_AT`] bytes and the row that crosses it.
    pub fn new() -> RowBuffer {
        RowBuffer { bytes: vec![0; FLUSH_AT + ROW_ROOM], len: 0 }
    }

    /// The text written since the last [`RowBuffer::write_to`].
    pub fn as_bytes(&self) -> &[u8] {
        &self.bytes[..self.len]
    }

    /// Whether [`FLUSH_AT`] bytes or more are waiting.
    pub fn is_full(&self) -> bool {
        self.len >= FLUSH_AT
    }

    /// Hands the text to `out` and empties the buffer.
    pub fn write_to(&mut self, out: &mut impl Write) -> io::Result<()> {
        out.write_all(&self.bytes[..self.len])?;
        self.len = 0;
        Ok(())
    }

    /// The `n` bytes after the text, growing the buffer when they are not there.
    #[inline]
    fn room(&mut self, n: usize) -> &mut [u8] {
        let end = self.len + n;
        if self.bytes.len() < end {
            self.grow(end);
        }
        &mut self.bytes[self.len..end]
    }

    /// Makes the buffer at least `length` bytes long.
    #[cold]
    #[inline(never)]
    fn grow(&mut self, length: usize) {
        self.bytes.resize(length.max(2 * self.bytes.len()), 0);
    }

    /// Appends one byte.
    #[inline]
    pub fn push(&mut self, byte: u8) {
        self.room(1)[0] = byte;
        self.len += 1;
    }

    /// Appends `text`.
    pub fn extend_from_slice(&mut self, text: &[u8]) {
        self.room(text.len()).copy_from_slice(text);
        self.len += text.len();
    }

    /// Appends `value` with exactly `decimals` decimals (at most [`MAX_DECIMALS`]; more are
    /// written as [`MAX_DECIMALS`]), rounded half away from zero, never a negative zero. It
    /// agrees with `format!` except, rarely, in the last digit of a value within rounding noise
    /// of a tie (`format!` rounds the exact binary value).
    #[inline]
    pub fn push_fixed(&mut self, value: f64, decimals: usize) {
        self.push_fixed_list([value], decimals);
    }

    /// Appends `values` separated by commas, each as [`RowBuffer::push_fixed`] writes it.
    ///
    /// A row's numbers in one call, with the number of decimals dispatched once (`joints` on the
    /// engraving program: 0.377 → 0.367 s, median of 10).
    #[inline]
    pub fn push_fixed_list<const N: usize>(&mut self, values: [f64; N], decimals: usize) {
        // One instance per number of decimals, so that the divisions by 10^decimals are by
        // constants (a multiplication) rather than a 64-bit `div`.
        match decimals {
            0 => self.push_list_with::<0, N>(values),
            1 => self.push_list_with::<1, N>(values),
            2 => self.push_list_with::<2, N>(values),
            3 => self.push_list_with::<3, N>(values),
            4 => self.push_list_with::<4, N>(values),
            5 => self.push_list_with::<5, N>(values),
            6 => self.push_list_with::<6, N>(values),
            7 => self.push_list_with::<7, N>(values),
            8 => self.push_list_with::<8, N>(values),
            9 => self.push_list_with::<9, N>(values),
            10 => self.push_list_with::<10, N>(values),
            11 => self.push_list_with::<11, N>(values),
            _ => self.push_list_with::<MAX_DECIMALS, N>(values),
        }
    }

    /// [`RowBuffer::push_fixed_list`] with `DECIMALS` decimals: the room for the whole row is
    /// made once, and the numbers are written into it inline, in a loop over a local slice
    /// (the buffer's pointer and length stay in registers).
    #[inline(always)]
    fn push_list_with<const DECIMALS: usize, const N: usize>(&mut self, values: [f64; N]) {
        let start = self.len;
        self.room(N * (FAST_WIDTH + 1));
        let room = &mut self.bytes[start..start + N * (FAST_WIDTH + 1)];
        let mut at = 0;
        for index in 0..N {
            if index > 0 {
                room[at] = b',';
                at += 1;
            }
            let slot: &mut [u8; FAST_WIDTH] =
                (&mut room[at..at + FAST_WIDTH]).try_into().expect("FAST_WIDTH bytes");
            match write_fixed::<DECIMALS>(slot, values[index]) {
                Some(length) => at += length,
                None => {
                    self.len = start + at;
                    self.push_slow::<DECIMALS>(&values[index..]);
                    return;
                }
            }
        }
        self.len = start + at;
    }

    /// The rest of a row from a number the fast path cannot write (`values[0]`) on.
    #[cold]
    #[inline(never)]
    fn push_slow<const DECIMALS: usize>(&mut self, values: &[f64]) {
        for (index, &value) in values.iter().enumerate() {
            if index == 0 {
                self.extend_from_slice(format_fixed(value, DECIMALS).as_bytes());
            } else {
                self.push(b',');
                self.push_list_with::<DECIMALS, 1>([value]);
            }
        }
    }
}

/// Appends `value` to `buffer` as [`RowBuffer::push_fixed`] does.
pub fn push_fixed(buffer: &mut Vec<u8>, value: f64, decimals: usize) {
    let mut row = RowBuffer { bytes: vec![0; FAST_WIDTH], len: 0 };
    row.push_fixed(value, decimals);
    buffer.extend_from_slice(row.as_bytes());
}

/// `value` with exactly `decimals` decimals, as `format!("{value:.decimals$}")` writes it (the
/// exact binary value rounded half to even), but never a negative zero (`-0.000` is `0.000`).
///
/// ```
/// assert_eq!(biscara_text::fixed(-0.0001, 3), "0.000");
/// assert_eq!(biscara_text::fixed(460.79872, 4), "460.7987");
/// ```
pub fn fixed(value: f64, decimals: usize) -> String {
    let text = format!("{value:.decimals$}");
    match text.strip_prefix('-') {
        Some(magnitude) if magnitude.bytes().all(|byte| byte == b'0' || byte == b'.') => {
            magnitude.to_owned()
        }
        _ => text,
    }
}

/// `value` rounded to `decimals` decimals (half away from zero), negative zero made zero: the
/// numbers of the JSON outputs, which serde_json prints shortest, so that they stay stable.
///
/// ```
/// assert_eq!(biscara_text::round_to(1.23456789, 6), 1.234568);
/// assert_eq!(biscara_text::round_to(-0.0000001, 6).to_string(), "0");
/// ```
pub fn round_to(value: f64, decimals: usize) -> f64 {
    let power = POWERS_OF_TEN.get(decimals).copied().unwrap_or_else(|| 10f64.powi(decimals as i32));
    (value * power).round() / power + 0.0
}

/// [`fixed`] with at most [`MAX_DECIMALS`] decimals: the slow path, for values too large to
/// scale exactly, infinities and NaN.
#[cold]
fn format_fixed(value: f64, decimals: usize) -> String {
    fixed(value, decimals.min(MAX_DECIMALS))
}

/// Writes `value` with `DECIMALS` decimals at the start of `out` and returns its length, or
/// `None` when it is too large for the fast path (or not finite); the bytes past the returned
/// length are scratch.
///
/// A scaled value below 10⁸ with at most seven decimals (every angle in radians, every length
/// below 100 mm at six decimals) is made by one [`eight_digits`] and stored from one 64-bit
/// register; a larger one by two, held in a 128-bit register. The integer part and the fraction
/// are each stored with one store. No loop, no branch on the digits, no load of what was just
/// stored (a store-forwarding stall). Inlined into the row's loop: as a call returning an
/// `Option`, it and the row's loop took 125 instructions a number (`joints` on the 20,000-line
/// engraving program, `valgrind --tool=callgrind`).
#[inline(always)]
fn write_fixed<const DECIMALS: usize>(out: &mut [u8; FAST_WIDTH], value: f64) -> Option<usize> {
    let scaled = value * POWERS_OF_TEN[DECIMALS];
    // One comparison, false for NaN too.
    let in_range = scaled.abs() < FAST_LIMIT;
    if !in_range {
        return None;
    }
    // Round half away from zero, as `f64::round`, by truncating `|x| + 0.5`; through i64, whose
    // conversion is one instruction where `round` and the u64 conversion are several.
    let magnitude = (scaled.abs() + 0.5) as i64 as u64;
    // Negative and not rounded to zero: for x < 0, 0.5 − x is the |x| + 0.5 just truncated, and
    // at least 1 exactly when the magnitude is not 0.
    let negative = 0.5 - scaled >= 1.0;
    out[0] = b'-';
    let at = usize::from(negative);
    if DECIMALS < 8 && magnitude < EIGHT_DIGITS {
        // The eight digits as text in one register, the first in the lowest byte.
        let text = eight_digits(magnitude) | ZERO_DIGITS;
        let mut integer_digits = 1;
        while integer_digits < 8 - DECIMALS
            && magnitude >= INTEGER_POWERS_OF_TEN[DECIMALS + integer_digits]
        {
            integer_digits += 1;
        }
        let integer_start = 8 - DECIMALS - integer_digits;
        out[at..at + 8].copy_from_slice(&(text >> (8 * integer_start)).to_le_bytes());
        let point = at + integer_digits;
        if DECIMALS == 0 {
            return Some(point);
        }
        out[point] = b'.';
        let fraction = text.checked_shr(8 * (8 - DECIMALS) as u32).unwrap_or(0);
        out[point + 1..point + 9].copy_from_slice(&fraction.to_le_bytes());
        return Some(point + 1 + DECIMALS);
    }
    write_wide::<DECIMALS>(out, magnitude, at)
}

/// [`write_fixed`] for a scaled value of up to sixteen digits (`magnitude`), after the sign
/// (`at` is 1 when there is one): the sixteen digits, first eight and last eight, in a 128-bit
/// register.
#[inline]
fn write_wide<const DECIMALS: usize>(
    out: &mut [u8; FAST_WIDTH],
    magnitude: u64,
    at: usize,
) -> Option<usize> {
    // Zero digits are zero bytes.
    let (first, last) = if magnitude < EIGHT_DIGITS {
        (0, eight_digits(magnitude))
    } else {
        (eight_digits(magnitude / EIGHT_DIGITS), eight_digits(magnitude % EIGHT_DIGITS))
    };
    // Counted on the magnitude, not on the digits, so that where the next number goes does not
    // wait for this one's digits (`joints` on the engraving program: 0.475 → 0.444 s); most
    // columns stop at the first comparison.
    let mut integer_digits = 1;
    while integer_digits < 16 - DECIMALS
        && magnitude >= INTEGER_POWERS_OF_TEN[DECIMALS + integer_digits]
    {
        integer_digits += 1;
    }
    // The digits as text, the first in the lowest byte (first in memory).
    let text = (u128::from(last | ZERO_DIGITS) << 64) | u128::from(first | ZERO_DIGITS);
    let integer_start = 16 - DECIMALS - integer_digits;
    out[at..at + 16].copy_from_slice(&(text >> (8 * integer_start)).to_le_bytes());
    let point = at + integer_digits;
    if DECIMALS == 0 {
        return Some(point);
    }
    out[point] = b'.';
    out[point + 1..point + 17].copy_from_slice(&(text >> (8 * (16 - DECIMALS))).to_le_bytes());
    Some(point + 1 + DECIMALS)
}

/// Eight `'0'`s: added to digit values 0–9 in every byte, they make text.
const ZERO_DIGITS: u64 = 0x3030_3030_3030_3030;

/// 10⁸: [`eight_digits`] takes numbers below it.
const EIGHT_DIGITS: u64 = 100_000_000;

/// The eight decimal digits of `x` < 10⁸ as values 0–9 in the eight bytes of a `u64`, the most
/// significant digit in the lowest byte (first in memory, little-endian): a few multiplications
/// and shifts on all digits at once instead of eight divisions (a known SIMD-within-a-register
/// technique). Each step splits every lane in two, the quotient by a power of ten found by a
/// multiplication and a shift exact over the lane's range: 10000 | ÷100 by ×10486 >> 20
/// (exact below 10⁴) | ÷10 by ×103 >> 10 (exact below 100).
#[inline]
fn eight_digits(x: u64) -> u64 {
    debug_assert!(x < EIGHT_DIGITS);
    // Two 32-bit lanes: the first four digits, the last four.
    let fours = (x / 10_000) | ((x % 10_000) << 32);
    // Four 16-bit lanes of two digits.
    let hundreds = ((fours * 10_486) >> 20) & 0x0000_007f_0000_007f;
    let twos = hundreds | ((fours - 100 * hundreds) << 16);
    // Eight 8-bit lanes of one digit.
    let tens = ((twos * 103) >> 10) & 0x000f_000f_000f_000f;
    tens | ((twos - 10 * tens) << 8)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What [`push_fixed`] writes, as text.
    fn pushed(value: f64, decimals: usize) -> String {
        let mut buffer = Vec::new();
        push_fixed(&mut buffer, value, decimals);
        String::from_utf8(buffer).unwrap()
    }

    #[test]
    fn fixed_agrees_with_format() {
        for value in [
            0.0,
            1.0,
            -1.5,
            9.9999996,
            99.5,
            100.0,
            -999.0,
            123.456789,
            -0.0004,
            0.0005,
            1e-7,
            460.798724079689,
            1e9,
            -42.0,
            3.99e15,
        ] {
            for (decimals, power) in POWERS_OF_TEN.into_iter().enumerate() {
                if (value * power).abs() < 1e15 || decimals == 0 {
                    assert_eq!(
                        pushed(value, decimals),
                        fixed(value, decimals),
                        "{value} {decimals}"
                    );
                }
            }
        }
        // Many values of every magnitude: equal to `format!` unless within noise of a tie.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..20000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let mantissa = (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            let value = mantissa * 10f64.powi((state % 16) as i32);
            for decimals in [0, 1, 2, 3, 5, 6, 9, 12] {
                let expected = fixed(value, decimals);
                let got = pushed(value, decimals);
                let scaled = value.abs() * 10f64.powi(decimals as i32);
                let near_tie = (scaled - scaled.trunc() - 0.5).abs() < 1e-6;
                if !near_tie && scaled < 1e15 {
                    assert_eq!(got, expected, "{value} with {decimals}");
                }
            }
        }
        assert_eq!(pushed(-0.0000001, 6), "0.000000");
        assert_eq!(pushed(-0.0, 0), "0");
        assert_eq!(pushed(1e300, 2).len(), 304);
        assert_eq!(pushed(f64::NAN, 3), "NaN");
        assert_eq!(pushed(f64::NEG_INFINITY, 3), "-inf");
        assert_eq!(pushed(-4e15, 0), "-4000000000000000");
        assert_eq!(pushed(-3.5e15, 0), "-3500000000000000");
    }

    #[test]
    fn fixed_text_never_prints_negative_zero() {
        assert_eq!(fixed(-0.0000001, 6), "0.000000");
        assert_eq!(fixed(-0.0, 3), "0.000");
        assert_eq!(fixed(-1.5, 3), "-1.500");
        assert_eq!(fixed(2.0, 0), "2");
        assert_eq!(fixed(f64::NEG_INFINITY, 2), "-inf");
    }

    #[test]
    fn round_to_matches_scaling_by_a_power_of_ten() {
        for value in [0.1234565, -2.5e-7, 123456.7890125, -0.0, 1e300] {
            assert_eq!(round_to(value, 6), (value * 1e6).round() / 1e6 + 0.0);
        }
        assert_eq!(round_to(0.5, 0), 1.0);
        assert_eq!(round_to(0.1234567, 3), 0.123);
    }

    #[test]
    fn eight_digits_are_the_decimal_digits() {
        let text =
            |x: u64| String::from_utf8((eight_digits(x) | ZERO_DIGITS).to_le_bytes().to_vec());
        let mut x = 0;
        while x < EIGHT_DIGITS {
            assert_eq!(text(x).unwrap(), format!("{x:08}"));
            // Every number below 10⁵, then a stride that visits every digit in every position.
            x += if x < 100_000 { 1 } else { 9_973 };
        }
        for x in [EIGHT_DIGITS - 1, 10_000_000, 12_345_678, 90_000_009] {
            assert_eq!(text(x).unwrap(), format!("{x:08}"));
        }
    }

    #[test]
    fn a_row_is_its_numbers_as_format_writes_them_with_commas() {
        // Signs, zeros rounded from below, one and two integer digits, 10⁸ and beyond at six
        // decimals, and numbers only the slow path writes, first, in the middle and last.
        let rows: [[f64; 5]; 4] = [
            [0.0, -0.0000004, 9.9999996, -99.9999994, 248.123],
            [1e300, 1.625, -2.25, 1e-7, 12345678.9],
            [0.25, f64::NAN, -0.75, f64::INFINITY, 7.0],
            [-3.0, 100.0, -1e9, 0.0000006, f64::NEG_INFINITY],
        ];
        for decimals in [0, 3, 6, 7, 9] {
            let mut row = RowBuffer::new();
            let mut expected = String::new();
            for values in rows {
                row.push_fixed_list(values, decimals);
                row.push(b'\n');
                let texts: Vec<String> =
                    values.iter().map(|&value| fixed(value, decimals)).collect();
                expected += &(texts.join(",") + "\n");
            }
            assert_eq!(String::from_utf8(row.as_bytes().to_vec()).unwrap(), expected);
        }
    }

    #[test]
    fn rows_grow_past_the_flush_mark() {
        let mut row = RowBuffer::new();
        let mut expected = Vec::new();
        for k in 0..20_000 {
            let value = f64::from(k) * 1.25e3 - 7.0;
            row.push_fixed(value, 4);
            row.push(b',');
            expected.extend_from_slice(format!("{value:.4},").as_bytes());
        }
        row.push_fixed(1e300, 1);
        expected.extend_from_slice(format!("{:.1}", 1e300).as_bytes());
        assert!(row.is_full());
        let mut out = Vec::new();
        row.write_to(&mut out).unwrap();
        assert_eq!(out, expected);
        assert!(row.as_bytes().is_empty() && !row.is_full());
    }
}
