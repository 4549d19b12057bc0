//! Reading a BARN reference path: a numpy `.npy` file holding an int64
//! array of shape (n, 2).
//!
//! The format (numpy's format module, versions 1–3) is a magic string, a
//! version, a header length, a Python dict literal with three keys
//! (`descr`, `fortran_order`, `shape`) and the raw data. That header is
//! parsed here rather than through a crate: the `.npy` crates parse
//! general Python literals with a grammar library and big-number types,
//! far more than three fixed keys need, in a core that is also built to
//! WebAssembly.

use super::{BarnError, BarnWorld};

/// The file's first six bytes.
const MAGIC: &[u8] = b"\x93NUMPY";

impl BarnWorld {
    /// The (row, col) cells of a `path_N.npy` file: little-endian int64
    /// (`descr` `<i8`), shape (n, 2), C or Fortran order, format version
    /// 1, 2 or 3.
    pub fn path_from_npy(bytes: &[u8]) -> Result<Vec<[i64; 2]>, BarnError> {
        let err = |m: &str| BarnError::Npy(m.to_string());
        if bytes.len() < 10 || &bytes[..6] != MAGIC {
            return Err(err("not a .npy file (no \\x93NUMPY magic)"));
        }
        let (len, start) = match bytes[6] {
            1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10usize),
            2 | 3 if bytes.len() >= 12 => (
                u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
                12,
            ),
            v => return Err(BarnError::Npy(format!("unsupported .npy version {v}"))),
        };
        let header = bytes
            .get(start..start.saturating_add(len))
            .ok_or_else(|| err("header runs past the end of the file"))?;
        let header = std::str::from_utf8(header).map_err(|_| err("header is not text"))?;
        let h = Header::parse(header).map_err(|m| BarnError::Npy(format!("header: {m}")))?;
        if h.descr != "<i8" {
            return Err(BarnError::Npy(format!(
                "dtype {:?}, a BARN path is little-endian int64 ('<i8')",
                h.descr
            )));
        }
        let n = match h.shape[..] {
            [n, 2] => n,
            _ => {
                return Err(BarnError::Npy(format!(
                    "shape {:?}, a BARN path is (n, 2)",
                    h.shape
                )))
            }
        };
        let data = &bytes[start + len..];
        if Some(data.len()) != n.checked_mul(16) {
            return Err(BarnError::Npy(format!(
                "{} data bytes for shape ({n}, 2) of int64 (expected {})",
                data.len(),
                n.saturating_mul(16)
            )));
        }
        let at = |k: usize| {
            let mut b = [0u8; 8];
            b.copy_from_slice(&data[8 * k..8 * k + 8]);
            i64::from_le_bytes(b)
        };
        Ok((0..n)
            .map(|i| {
                if h.fortran_order {
                    [at(i), at(n + i)]
                } else {
                    [at(2 * i), at(2 * i + 1)]
                }
            })
            .collect())
    }
}

/// The three keys of a `.npy` header.
#[derive(Debug, PartialEq)]
struct Header {
    descr: String,
    fortran_order: bool,
    shape: Vec<usize>,
}

impl Header {
    /// Parses `{'descr': '<i8', 'fortran_order': False, 'shape': (37, 2), }`
    /// (keys in any order, trailing commas and padding allowed).
    fn parse(text: &str) -> Result<Header, String> {
        let mut p = Lexer {
            s: text.trim_end_matches(['\n', ' ', '\0']).trim_start(),
        };
        p.eat('{')?;
        let (mut descr, mut fortran, mut shape) = (None, None, None);
        while !p.peek('}') {
            let key = p.string()?;
            p.eat(':')?;
            match key.as_str() {
                "descr" => descr = Some(p.string()?),
                "fortran_order" => fortran = Some(p.boolean()?),
                "shape" => shape = Some(p.tuple()?),
                other => return Err(format!("unknown key {other:?}")),
            }
            if !p.peek('}') {
                p.eat(',')?;
            }
        }
        p.eat('}')?;
        if !p.s.is_empty() {
            return Err(format!("text after the dict: {:?}", p.s));
        }
        match (descr, fortran, shape) {
            (Some(descr), Some(fortran_order), Some(shape)) => Ok(Header {
                descr,
                fortran_order,
                shape,
            }),
            _ => Err("missing descr, fortran_order or shape".into()),
        }
    }
}

/// A cursor over the header's Python literal.
struct Lexer<'a> {
    s: &'a str,
}

impl Lexer<'_> {
    fn peek(&mut self, c: char) -> bool {
        self.s = self.s.trim_start();
        self.s.starts_with(c)
    }

    fn eat(&mut self, c: char) -> Result<(), String> {
        if self.peek(c) {
            self.s = &self.s[c.len_utf8()..];
            Ok(())
        } else {
            Err(format!("expected {c:?} at {:?}", self.s))
        }
    }

    /// A quoted string without escapes (numpy writes none in these keys).
    fn string(&mut self) -> Result<String, String> {
        self.s = self.s.trim_start();
        let q = self
            .s
            .chars()
            .next()
            .filter(|&q| q == '\'' || q == '"')
            .ok_or_else(|| format!("expected a string at {:?}", self.s))?;
        let end = self.s[1..]
            .find(q)
            .ok_or_else(|| "unterminated string".to_string())?;
        let out = self.s[1..1 + end].to_string();
        self.s = &self.s[end + 2..];
        Ok(out)
    }

    fn boolean(&mut self) -> Result<bool, String> {
        self.s = self.s.trim_start();
        for (word, v) in [("True", true), ("False", false)] {
            if let Some(rest) = self.s.strip_prefix(word) {
                self.s = rest;
                return Ok(v);
            }
        }
        Err(format!("expected True or False at {:?}", self.s))
    }

    /// A tuple of non-negative integers: `()`, `(5,)`, `(37, 2)`.
    fn tuple(&mut self) -> Result<Vec<usize>, String> {
        self.eat('(')?;
        let mut out = Vec::new();
        while !self.peek(')') {
            let digits = self
                .s
                .find(|c: char| !c.is_ascii_digit())
                .unwrap_or(self.s.len());
            let n = self.s[..digits]
                .parse::<usize>()
                .map_err(|_| format!("expected a dimension at {:?}", self.s))?;
            out.push(n);
            self.s = &self.s[digits..];
            if !self.peek(')') {
                self.eat(',')?;
            }
        }
        self.eat(')')?;
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A version-1 `.npy` file of `values` with shape (n, 2) and `header`'s
    /// dict, padded as numpy pads it.
    fn npy(dict: &str, values: &[i64]) -> Vec<u8> {
        let mut h = dict.to_string();
        while (10 + h.len() + 1) % 64 != 0 {
            h.push(' ');
        }
        h.push('\n');
        let mut b = MAGIC.to_vec();
        b.extend([1, 0]);
        b.extend((h.len() as u16).to_le_bytes());
        b.extend(h.as_bytes());
        for v in values {
            b.extend(v.to_le_bytes());
        }
        b
    }

    #[test]
    fn reads_c_and_fortran_order_and_version_2() {
        let c = npy(
            "{'descr': '<i8', 'fortran_order': False, 'shape': (3, 2), }",
            &[1, 2, 3, 4, -5, 6],
        );
        assert_eq!(
            BarnWorld::path_from_npy(&c).unwrap(),
            vec![[1, 2], [3, 4], [-5, 6]]
        );
        let f = npy(
            "{'shape': (3, 2), 'fortran_order': True, 'descr': '<i8'}",
            &[1, 3, -5, 2, 4, 6],
        );
        assert_eq!(
            BarnWorld::path_from_npy(&f).unwrap(),
            vec![[1, 2], [3, 4], [-5, 6]]
        );
        // Version 2: a four-byte header length.
        let mut v2 = c.clone();
        v2[6] = 2;
        let len = u16::from_le_bytes([c[8], c[9]]) as u32;
        v2.splice(8..10, len.to_le_bytes());
        assert_eq!(
            BarnWorld::path_from_npy(&v2).unwrap(),
            vec![[1, 2], [3, 4], [-5, 6]]
        );
    }

    #[test]
    fn malformed_npy_gives_typed_errors() {
        let ok = "{'descr': '<i8', 'fortran_order': False, 'shape': (2, 2), }";
        let cases: Vec<(Vec<u8>, &str)> = vec![
            (b"PK\x03\x04 not npy".to_vec(), "magic"),
            (b"\x93NUMPY".to_vec(), "magic"),
            (npy(ok, &[1, 2, 3]), "data bytes"),
            (npy(ok, &[1, 2, 3, 4, 5]), "data bytes"),
            (
                npy(
                    "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 2), }",
                    &[0; 4],
                ),
                "dtype",
            ),
            (
                npy(
                    "{'descr': '<i8', 'fortran_order': False, 'shape': (4,), }",
                    &[0; 4],
                ),
                "shape",
            ),
            (
                npy(
                    "{'descr': '<i8', 'fortran_order': Maybe, 'shape': (2, 2), }",
                    &[0; 4],
                ),
                "True or False",
            ),
            (
                npy("{'descr': '<i8', 'shape': (2, 2), }", &[0; 4]),
                "missing",
            ),
            (
                npy(
                    "{'descr': '<i8', 'fortran_order': False, 'shape': (2, 2)",
                    &[0; 4],
                ),
                "expected",
            ),
        ];
        for (bytes, needle) in cases {
            match BarnWorld::path_from_npy(&bytes) {
                Err(BarnError::Npy(m)) => assert!(m.contains(needle), "{m:?} lacks {needle:?}"),
                other => panic!("expected an Npy error with {needle:?}, got {other:?}"),
            }
        }
        // A header length past the end of the file.
        let mut cut = npy(ok, &[0; 4]);
        cut.truncate(40);
        assert!(matches!(
            BarnWorld::path_from_npy(&cut),
            Err(BarnError::Npy(_))
        ));
        let mut v9 = npy(ok, &[0; 4]);
        v9[6] = 9;
        assert!(
            matches!(BarnWorld::path_from_npy(&v9), Err(BarnError::Npy(m)) if m.contains("version 9"))
        );
    }
}
