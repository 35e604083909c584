//! A whitespace tokenizer over a whole file that tracks lines, checks declared counts
//! against the bytes left, and reads binary blocks: shared by every text reader.

use std::path::Path;
use std::str::FromStr;

use super::error::{IoError, Location};

/// Tokenizer state over the bytes of one file.
#[derive(Debug)]
pub struct Lexer<'a> {
    data: &'a [u8],
    pos: usize,
    line: usize,
    tok_line: usize,
    path: &'a Path,
    comment: Option<u8>,
}

impl<'a> Lexer<'a> {
    /// A lexer over `data`; `comment` starts a comment running to the end of the line.
    pub fn new(path: &'a Path, data: &'a [u8], comment: Option<u8>) -> Self {
        Lexer { data, pos: 0, line: 1, tok_line: 1, path, comment }
    }

    pub fn path(&self) -> &'a Path {
        self.path
    }

    /// Line of the last token read.
    pub fn line(&self) -> u32 {
        self.tok_line as u32
    }

    /// Error at the line of the last token read.
    pub fn err(&self, msg: impl Into<String>) -> IoError {
        IoError::Parse { path: self.path.to_path_buf(), at: Location::Line(self.tok_line), msg: msg.into() }
    }

    /// Error at a byte offset (binary data).
    pub fn err_at_byte(&self, msg: impl Into<String>) -> IoError {
        IoError::Parse { path: self.path.to_path_buf(), at: Location::Byte(self.pos), msg: msg.into() }
    }

    pub fn remaining(&self) -> usize {
        self.data.len() - self.pos
    }

    fn skip_ws(&mut self) {
        while self.pos < self.data.len() {
            let c = self.data[self.pos];
            if c == b'\n' {
                self.line += 1;
                self.pos += 1;
            } else if c.is_ascii_whitespace() {
                self.pos += 1;
            } else if Some(c) == self.comment {
                while self.pos < self.data.len() && self.data[self.pos] != b'\n' {
                    self.pos += 1;
                }
            } else {
                break;
            }
        }
    }

    /// The next token, or None at end of input.
    pub fn token(&mut self) -> Option<&'a str> {
        self.skip_ws();
        self.tok_line = self.line;
        let start = self.pos;
        while self.pos < self.data.len() && !self.data[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        if start == self.pos {
            return None;
        }
        Some(std::str::from_utf8(&self.data[start..self.pos]).unwrap_or("\u{FFFD}"))
    }

    /// The next token without consuming it.
    pub fn peek(&mut self) -> Option<&'a str> {
        let (pos, line, tl) = (self.pos, self.line, self.tok_line);
        let t = self.token();
        self.pos = pos;
        self.line = line;
        self.tok_line = tl;
        t
    }

    /// The next token; an error naming `what` at end of input.
    pub fn expect(&mut self, what: &str) -> Result<&'a str, IoError> {
        match self.token() {
            Some(t) => Ok(t),
            None => {
                // End of file is reported on the last line that has content.
                let ends_nl = self.data.last() == Some(&b'\n');
                self.tok_line = if ends_nl { (self.line - 1).max(1) } else { self.line };
                Err(self.err(format!("expected {what}, found end of file")))
            }
        }
    }

    /// The next token, which must equal `word` (ASCII case-insensitive).
    pub fn expect_word(&mut self, word: &str) -> Result<(), IoError> {
        let t = self.expect(&format!("'{word}'"))?;
        if t.eq_ignore_ascii_case(word) { Ok(()) } else { Err(self.err(format!("expected '{word}', found '{t}'"))) }
    }

    /// The next token as an integer, parsed straight from the bytes (hot path of every
    /// connectivity list); anything unusual takes the checked path.
    pub fn int(&mut self, what: &str) -> Result<i64, IoError> {
        self.skip_ws();
        self.tok_line = self.line;
        let d = self.data;
        let mut i = self.pos;
        let sign = match d.get(i) {
            Some(b'-') => -1,
            Some(b'+') => 1,
            _ => 0,
        };
        if sign != 0 {
            i += 1;
        }
        let digits = i;
        let mut v: i64 = 0;
        // 18 digits cannot overflow an i64.
        while i < d.len() && i - digits < 18 && d[i].is_ascii_digit() {
            v = v * 10 + (d[i] - b'0') as i64;
            i += 1;
        }
        if i > digits && (i == d.len() || d[i].is_ascii_whitespace()) {
            self.pos = i;
            return Ok(if sign < 0 { -v } else { v });
        }
        // Not a short plain integer: take the checked path (and its message).
        self.parse::<i64>(what)
    }

    /// The next token parsed as `T`.
    pub fn parse<T: FromStr>(&mut self, what: &str) -> Result<T, IoError> {
        let t = self.expect(what)?;
        t.parse::<T>().map_err(|_| self.err(format!("expected {what}, found '{}'", clip(t))))
    }

    /// A finite floating-point number.
    pub fn f64(&mut self, what: &str) -> Result<f64, IoError> {
        self.skip_ws();
        if let Some((x, end)) = plain_decimal(self.data, self.pos) {
            self.tok_line = self.line;
            self.pos = end;
            return Ok(x);
        }
        let x: f64 = self.parse(what)?;
        if x.is_finite() { Ok(x) } else { Err(self.err(format!("expected {what} (a finite number), found {x}"))) }
    }

    /// A point: three finite coordinates.
    pub fn point(&mut self) -> Result<[f64; 3], IoError> {
        Ok([self.f64("an x coordinate")?, self.f64("a y coordinate")?, self.f64("a z coordinate")?])
    }

    /// A declared item count, refused when `count` items of at least `min_bytes` each
    /// cannot fit in the rest of the file (so no allocation follows a lie).
    pub fn count(&mut self, what: &str, min_bytes: usize) -> Result<usize, IoError> {
        let n: i64 = self.parse(&format!("the number of {what}"))?;
        self.check_count(n, what, min_bytes)
    }

    /// See [`count`](Self::count), for a count already parsed.
    pub fn check_count(&self, n: i64, what: &str, min_bytes: usize) -> Result<usize, IoError> {
        if n < 0 {
            return Err(self.err(format!("expected a non-negative number of {what}, found {n}")));
        }
        let need = (n as u128) * (min_bytes as u128);
        if need > self.remaining() as u128 {
            return Err(self.err(format!(
                "file declares {n} {what}, which need at least {need} more bytes, but only {} remain",
                self.remaining()
            )));
        }
        Ok(n as usize)
    }

    /// A node index: an integer in `0..limit` after subtracting `base` (1 for 1-based formats).
    pub fn index(&mut self, base: i64, limit: usize, what: &str) -> Result<u32, IoError> {
        let v = self.int(what)?;
        let i = v - base;
        if i < 0 || i as u128 >= limit as u128 {
            let (lo, hi) = (base, limit as i64 - 1 + base);
            return Err(self.err(format!("{what} {v} is out of range (valid: {lo}..={hi})")));
        }
        Ok(i as u32)
    }

    /// Skips to the start of the next line.
    pub fn next_line(&mut self) {
        while self.pos < self.data.len() && self.data[self.pos] != b'\n' {
            self.pos += 1;
        }
        if self.pos < self.data.len() {
            self.pos += 1;
            self.line += 1;
        }
    }

    /// The rest of the current line (without the newline), consuming it.
    pub fn rest_of_line(&mut self) -> &'a str {
        self.tok_line = self.line;
        let start = self.pos;
        while self.pos < self.data.len() && self.data[self.pos] != b'\n' {
            self.pos += 1;
        }
        let s = std::str::from_utf8(&self.data[start..self.pos]).unwrap_or("");
        self.next_line();
        s.trim_end_matches('\r')
    }

    /// `n` raw bytes (binary blocks).
    pub fn bytes(&mut self, n: usize, what: &str) -> Result<&'a [u8], IoError> {
        if n > self.remaining() {
            return Err(self.err_at_byte(format!("expected {n} bytes of {what}, but only {} remain", self.remaining())));
        }
        let b = &self.data[self.pos..self.pos + n];
        self.line += b.iter().filter(|&&c| c == b'\n').count();
        self.pos += n;
        Ok(b)
    }
}

/// A token shortened for error messages.
pub fn clip(t: &str) -> String {
    if t.chars().count() > 40 { format!("{}…", t.chars().take(40).collect::<String>()) } else { t.to_string() }
}

/// Powers of ten that are exact in an f64.
const EXACT_POWERS: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20,
    1e21, 1e22,
];

/// A token of the form `[-+]digits[.digits]` (no exponent) with at most 15 digits,
/// read at `pos`, and the position after it. Such a number is m / 10^k with m and 10^k
/// exact in an f64, so the one division is correctly rounded: the same value as
/// `str::parse` (Clinger's fast path). Other tokens return None for the general parser.
fn plain_decimal(d: &[u8], pos: usize) -> Option<(f64, usize)> {
    let negative = d.get(pos) == Some(&b'-');
    let mut i = pos + usize::from(matches!(d.get(pos), Some(b'-' | b'+')));
    let (mut m, mut digits, mut frac) = (0u64, 0usize, 0usize);
    let mut seen_point = false;
    while let Some(&c) = d.get(i) {
        if c.is_ascii_digit() {
            m = m * 10 + (c - b'0') as u64;
            digits += 1;
            frac += usize::from(seen_point);
            if digits > 15 {
                return None;
            }
        } else if c == b'.' && !seen_point {
            seen_point = true;
        } else {
            break;
        }
        i += 1;
    }
    if digits == 0 || d.get(i).is_some_and(|c| !c.is_ascii_whitespace()) {
        return None;
    }
    let x = m as f64 / EXACT_POWERS[frac];
    Some((if negative { -x } else { x }, i))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_decimal_fast_path_equals_the_standard_parser() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let mut checked = 0;
        for _ in 0..200_000 {
            let (int_digits, frac_digits) = ((next() % 9) as usize, (next() % 12) as usize);
            let digit = |r: u64| char::from(b'0' + (r % 10) as u8);
            let mut t = String::from(["", "-", "+"][(next() % 3) as usize]);
            (0..int_digits).for_each(|_| t.push(digit(next())));
            if next() % 4 != 0 {
                t.push('.');
                (0..frac_digits).for_each(|_| t.push(digit(next())));
            }
            let fast = plain_decimal(t.as_bytes(), 0).map(|(x, end)| {
                assert_eq!(end, t.len(), "{t}");
                x
            });
            match (fast, t.parse::<f64>()) {
                (Some(x), Ok(y)) => {
                    assert_eq!(x.to_bits(), y.to_bits(), "{t}");
                    checked += 1;
                }
                (Some(x), Err(_)) => panic!("{t} read as {x} but is not a number"),
                (None, _) => {}
            }
        }
        assert!(checked > 100_000, "the fast path took only {checked} of the tokens");
        // Tokens it leaves to the general parser.
        for t in ["1e5", "1.2.3", "nan", "inf", "1234567890123456", "-", ".", "12a"] {
            assert!(plain_decimal(t.as_bytes(), 0).is_none(), "{t}");
        }
        assert_eq!(plain_decimal(b"  2.5 ", 2), Some((2.5, 5)));
    }
}
