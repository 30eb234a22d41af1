//! Mutations: byte-level ones (flip, insert, delete, overwrite with interesting integers and
//! floats, truncate, splice from another seed) and structure-aware ones for text formats
//! (replace a number by an edge case, splice, delete or repeat lines and sections, swap words).

use rand::{Rng, RngCore};
use rand_chacha::ChaCha8Rng;

/// Numbers that break parsers and geometry: zeros, non-finite values, extremes, huge counts.
const NUMBERS: &[&str] = &[
    "0",
    "-0",
    "0.0",
    "-0.0",
    "NaN",
    "nan",
    "-nan",
    "inf",
    "-inf",
    "+inf",
    "infinity",
    "1e308",
    "-1e308",
    "1e309",
    "1e-308",
    "5e-324",
    "1e400",
    "-1",
    "1",
    "2",
    "3",
    "7",
    "4294967295",
    "4294967296",
    "2147483647",
    "-2147483648",
    "18446744073709551615",
    "18446744073709551616",
    "9223372036854775807",
    "99999999999999999999999",
    "1e100",
    "1e101",
    "-1e100",
    "1e15",
    "1000000",
    "100000000",
    "0x10",
    "1.",
    ".5",
    "1e",
    "--1",
    "3.141592653589793",
    "6.283185307179586",
    "1e-9",
    "1e-300",
    "-1e-300",
];

/// Tokens worth inserting into text formats.
const TOKENS: &[&str] = &[
    "[",
    "]",
    "[[",
    "]]",
    "{",
    "}",
    "=",
    "\"",
    "'",
    ",",
    "#",
    "\n",
    "\r\n",
    "<",
    ">",
    "/>",
    "</",
    " ",
    "\t",
    "\0",
    "\u{feff}",
    "é",
    "..",
    "/",
    "\\",
    "-",
    "e",
    "f ",
    "v ",
    "vn ",
    "vt ",
    "facet",
    "endfacet",
    "vertex",
    "solid",
    "endsolid",
    "<p>",
    "</p>",
    "count=\"",
    "stride=\"",
    "offset=\"",
    "<input semantic=\"VERTEX\" source=\"#",
    "<instance_node url=\"#",
    "id=\"",
    "#",
    "[[obstacle]]\n",
    "[[query]]\n",
    "[robot]\n",
    "[space]\n",
    "[problem]\n",
];

/// Integers for binary formats (little-endian), including varint prefixes of bincode.
const INTS: &[u64] = &[
    0,
    1,
    2,
    0x7f,
    0x80,
    0xff,
    0x100,
    0xfb,
    0xfc,
    0xfd,
    0xfe,
    0xffff,
    0x7fff_ffff,
    0xffff_ffff,
    0x1_0000_0000,
    u64::MAX,
    i64::MAX as u64,
    u32::MAX as u64 + 1,
];

/// How the bytes of a target are best mutated.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Line-oriented text (TOML, INI, OBJ, ASCII STL, XML, query files).
    Text,
    /// Binary (roadmap payloads, binary STL) mixed with text (STL may be either).
    Binary,
}

/// The mutation engine: deterministic for a seed.
pub struct Mutator {
    /// The random source.
    pub rng: ChaCha8Rng,
}

fn lines(bytes: &[u8]) -> Vec<&[u8]> {
    bytes.split_inclusive(|&b| b == b'\n').collect()
}

impl Mutator {
    /// A mutator seeded with `seed`.
    pub fn new(seed: u64) -> Mutator {
        use rand::SeedableRng;
        Mutator {
            rng: ChaCha8Rng::seed_from_u64(seed),
        }
    }

    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            self.rng.random_range(0..n)
        }
    }

    fn chance(&mut self, p: f64) -> bool {
        self.rng.random_bool(p)
    }

    /// `base` mutated 1–6 times (a stack of mutations), `others` giving splice material.
    pub fn mutate(&mut self, base: &[u8], others: &[Vec<u8>], kind: Kind) -> Vec<u8> {
        let mut data = base.to_vec();
        let most = if self.chance(0.7) { 2 } else { 6 };
        let n = 1 + self.below(most);
        for _ in 0..n {
            let other = &others[self.below(others.len())];
            self.once(&mut data, other, kind);
            if data.len() > 1 << 20 {
                data.truncate(1 << 20);
            }
        }
        data
    }

    fn once(&mut self, data: &mut Vec<u8>, other: &[u8], kind: Kind) {
        let ops = if kind == Kind::Text { 16 } else { 16 + 4 };
        match self.below(ops) {
            0..=3 => self.replace_number(data),
            4 => self.splice_lines(data, other),
            5 => self.delete_lines(data),
            6 => self.repeat_lines(data),
            7 => self.swap_words(data, other),
            8 => self.insert_token(data),
            9 => self.truncate(data),
            10 => self.flip_bit(data),
            11 => self.insert_byte(data),
            12 => self.delete_bytes(data),
            13 => self.splice_bytes(data, other),
            14 => self.splice_section(data, other),
            15 => self.perturb_number(data),
            16 | 17 => self.write_int(data),
            18 => self.write_float(data),
            _ => self.set_byte(data),
        }
    }

    fn number_spans(data: &[u8]) -> Vec<(usize, usize)> {
        let mut spans = Vec::new();
        let mut i = 0;
        while i < data.len() {
            let start = i;
            let mut digit = false;
            while i < data.len()
                && matches!(data[i], b'0'..=b'9' | b'.' | b'e' | b'E' | b'+' | b'-')
            {
                digit |= data[i].is_ascii_digit();
                i += 1;
            }
            if digit {
                spans.push((start, i));
            }
            if i == start {
                i += 1;
            }
        }
        spans
    }

    fn replace_number(&mut self, data: &mut Vec<u8>) {
        let spans = Self::number_spans(data);
        if spans.is_empty() {
            return self.insert_token(data);
        }
        let (a, b) = spans[self.below(spans.len())];
        let with = NUMBERS[self.below(NUMBERS.len())];
        data.splice(a..b, with.bytes());
    }

    fn perturb_number(&mut self, data: &mut Vec<u8>) {
        let spans = Self::number_spans(data);
        if spans.is_empty() {
            return;
        }
        let (a, b) = spans[self.below(spans.len())];
        let Ok(x) = std::str::from_utf8(&data[a..b])
            .unwrap_or("")
            .parse::<f64>()
        else {
            return;
        };
        let y = match self.below(6) {
            0 => -x,
            1 => x * 10f64.powi(self.below(20) as i32),
            2 => x + 1.0,
            3 => x - 1.0,
            4 => x.trunc(),
            _ => x * (1.0 + 1e-12),
        };
        let text = if self.chance(0.5) {
            format!("{y}")
        } else {
            format!("{y:e}")
        };
        data.splice(a..b, text.bytes());
    }

    fn splice_lines(&mut self, data: &mut Vec<u8>, other: &[u8]) {
        let from = lines(other);
        if from.is_empty() {
            return;
        }
        let k = self.below(from.len());
        let n = 1 + self.below(4.min(from.len() - k));
        let chunk: Vec<u8> = from[k..k + n].concat();
        let at = self.line_start(data);
        data.splice(at..at, chunk);
    }

    fn line_start(&mut self, data: &[u8]) -> usize {
        let starts: Vec<usize> = std::iter::once(0)
            .chain(
                data.iter()
                    .enumerate()
                    .filter(|(_, &b)| b == b'\n')
                    .map(|(i, _)| i + 1),
            )
            .collect();
        starts[self.below(starts.len())]
    }

    fn line_range(&mut self, data: &[u8]) -> Option<(usize, usize)> {
        let ls = lines(data);
        if ls.is_empty() {
            return None;
        }
        let k = self.below(ls.len());
        let n = 1 + self.below(3.min(ls.len() - k));
        let a: usize = ls[..k].iter().map(|l| l.len()).sum();
        let b = a + ls[k..k + n].iter().map(|l| l.len()).sum::<usize>();
        Some((a, b))
    }

    fn delete_lines(&mut self, data: &mut Vec<u8>) {
        if let Some((a, b)) = self.line_range(data) {
            data.drain(a..b);
        }
    }

    fn repeat_lines(&mut self, data: &mut Vec<u8>) {
        if let Some((a, b)) = self.line_range(data) {
            let times = if self.chance(0.8) {
                1
            } else {
                1 + self.below(200)
            };
            let chunk = data[a..b].repeat(times);
            data.splice(b..b, chunk);
        }
    }

    /// A section: from a line starting with `[` or `<` to the next such line.
    fn splice_section(&mut self, data: &mut Vec<u8>, other: &[u8]) {
        let from = lines(other);
        let heads: Vec<usize> = from
            .iter()
            .enumerate()
            .filter(|(_, l)| matches!(l.trim_ascii_start().first(), Some(b'[' | b'<')))
            .map(|(i, _)| i)
            .collect();
        if heads.is_empty() {
            return self.splice_lines(data, other);
        }
        let k = heads[self.below(heads.len())];
        let end = (k + 1..from.len())
            .find(|&i| matches!(from[i].trim_ascii_start().first(), Some(b'[' | b'<')))
            .unwrap_or(from.len());
        let chunk: Vec<u8> = from[k..end.min(k + 40)].concat();
        let at = self.line_start(data);
        data.splice(at..at, chunk);
    }

    fn words(data: &[u8]) -> Vec<(usize, usize)> {
        let mut spans = Vec::new();
        let mut i = 0;
        while i < data.len() {
            let start = i;
            while i < data.len()
                && (data[i].is_ascii_alphanumeric() || data[i] == b'_' || data[i] == b'.')
            {
                i += 1;
            }
            if i > start {
                spans.push((start, i));
            } else {
                i += 1;
            }
        }
        spans
    }

    fn swap_words(&mut self, data: &mut Vec<u8>, other: &[u8]) {
        let (mine, theirs) = (Self::words(data), Self::words(other));
        if mine.is_empty() || theirs.is_empty() {
            return;
        }
        let (a, b) = mine[self.below(mine.len())];
        let (c, d) = theirs[self.below(theirs.len())];
        data.splice(a..b, other[c..d].iter().copied());
    }

    fn insert_token(&mut self, data: &mut Vec<u8>) {
        let t = TOKENS[self.below(TOKENS.len())];
        let at = self.below(data.len() + 1);
        data.splice(at..at, t.bytes());
    }

    fn truncate(&mut self, data: &mut Vec<u8>) {
        let at = self.below(data.len() + 1);
        data.truncate(at);
    }

    fn flip_bit(&mut self, data: &mut [u8]) {
        if !data.is_empty() {
            let i = self.below(data.len());
            data[i] ^= 1 << self.below(8);
        }
    }

    fn set_byte(&mut self, data: &mut [u8]) {
        if !data.is_empty() {
            let i = self.below(data.len());
            data[i] = [0, 0xff, 0x7f, 0x80, 0xfb, 0xfc, 0xfd, 0xfe, 1][self.below(9)];
        }
    }

    fn insert_byte(&mut self, data: &mut Vec<u8>) {
        let at = self.below(data.len() + 1);
        let b = self.rng.next_u32() as u8;
        data.insert(at, b);
    }

    fn delete_bytes(&mut self, data: &mut Vec<u8>) {
        if data.is_empty() {
            return;
        }
        let a = self.below(data.len());
        let n = 1 + self.below(16.min(data.len() - a));
        data.drain(a..a + n);
    }

    fn splice_bytes(&mut self, data: &mut Vec<u8>, other: &[u8]) {
        if other.is_empty() {
            return;
        }
        let c = self.below(other.len());
        let n = 1 + self.below(64.min(other.len() - c));
        let at = self.below(data.len() + 1);
        if self.chance(0.5) {
            let end = (at + n).min(data.len());
            data.splice(at..end, other[c..c + n].iter().copied());
        } else {
            data.splice(at..at, other[c..c + n].iter().copied());
        }
    }

    fn write_int(&mut self, data: &mut Vec<u8>) {
        let v = INTS[self.below(INTS.len())];
        let width = [1, 2, 4, 8][self.below(4)];
        let bytes = &v.to_le_bytes()[..width];
        let at = self.below(data.len() + 1);
        if self.chance(0.5) {
            data.splice(at..at, bytes.iter().copied());
        } else {
            let end = (at + width).min(data.len());
            data.splice(at..end, bytes.iter().copied());
        }
    }

    fn write_float(&mut self, data: &mut Vec<u8>) {
        let v = [
            f64::NAN,
            f64::INFINITY,
            -f64::INFINITY,
            0.0,
            -0.0,
            1e308,
            f64::MIN_POSITIVE,
            1e100,
        ];
        let x = v[self.below(v.len())];
        let bytes: Vec<u8> = if self.chance(0.5) {
            x.to_le_bytes().to_vec()
        } else {
            (x as f32).to_le_bytes().to_vec()
        };
        let at = self.below(data.len() + 1);
        let end = (at + bytes.len()).min(data.len());
        data.splice(at..end, bytes);
    }
}
