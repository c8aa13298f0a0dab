//! One input record: its tokens and typed, keyword-addressed field access with error spans.

use super::lexer::{tokenize, Line};
use crate::error::{Error, Result, Span};
use std::cell::RefCell;

/// A tokenized record. Field lookup scans all tokens for the first exact keyword match
/// (OOFEM's `giveKeywordIndx`); consumed tokens are remembered to warn about unread ones.
#[derive(Debug)]
pub struct Record {
    pub line: Line,
    pub tokens: Vec<String>,
    used: RefCell<Vec<bool>>,
}

impl Record {
    pub fn new(line: Line) -> Record {
        let tokens = tokenize(&line.text);
        let used = RefCell::new(vec![false; tokens.len()]);
        Record { line, tokens, used }
    }

    pub fn span(&self) -> Span {
        Span {
            file: self.line.file.as_ref().clone(),
            line: self.line.line,
            record: self.line.text.trim().to_string(),
        }
    }

    /// An input error located at this record.
    pub fn error(&self, msg: impl Into<String>) -> Error {
        Error::Input {
            span: self.span(),
            msg: msg.into(),
        }
    }

    /// The record keyword (first token, lower case).
    pub fn keyword(&self) -> &str {
        self.mark(0, 1);
        self.tokens.first().map(String::as_str).unwrap_or("")
    }

    fn mark(&self, from: usize, n: usize) {
        let mut used = self.used.borrow_mut();
        for u in used.iter_mut().skip(from).take(n) {
            *u = true;
        }
    }

    fn find(&self, key: &str) -> Option<usize> {
        self.tokens.iter().position(|t| t == key)
    }

    /// True if the flag keyword is present.
    pub fn flag(&self, key: &str) -> bool {
        match self.find(key) {
            Some(i) => {
                self.mark(i, 1);
                true
            }
            None => false,
        }
    }

    fn value_token(&self, key: &str, offset: usize) -> Result<Option<&str>> {
        let Some(i) = self.find(key) else {
            return Ok(None);
        };
        self.mark(i, 1);
        match self.tokens.get(i + 1 + offset) {
            Some(t) => {
                self.mark(i + 1 + offset, 1);
                Ok(Some(t))
            }
            None => Err(self.error(format!("keyword `{key}` is missing its value"))),
        }
    }

    fn parse_int(&self, key: &str, t: &str) -> Result<i64> {
        t.parse::<i64>()
            .map_err(|_| self.error(format!("`{key}` expects an integer, found `{t}`")))
    }

    fn parse_float(&self, key: &str, t: &str) -> Result<f64> {
        let v = parse_f64(t)
            .ok_or_else(|| self.error(format!("`{key}` expects a number, found `{t}`")))?;
        if !v.is_finite() {
            return Err(self.error(format!(
                "`{key}` value `{t}` is beyond the range of double precision (about 1.8e308)"
            )));
        }
        Ok(v)
    }

    pub fn opt_int(&self, key: &str) -> Result<Option<i64>> {
        match self.value_token(key, 0)? {
            Some(t) => Ok(Some(self.parse_int(key, t)?)),
            None => Ok(None),
        }
    }

    pub fn int(&self, key: &str) -> Result<i64> {
        self.opt_int(key)?
            .ok_or_else(|| self.error(format!("missing required keyword `{key}`")))
    }

    /// A non-negative count or index.
    pub fn opt_usize(&self, key: &str) -> Result<Option<usize>> {
        match self.opt_int(key)? {
            Some(v) if v < 0 => Err(self.error(format!("`{key}` must not be negative, found {v}"))),
            Some(v) => Ok(Some(v as usize)),
            None => Ok(None),
        }
    }

    pub fn usize(&self, key: &str) -> Result<usize> {
        self.opt_usize(key)?
            .ok_or_else(|| self.error(format!("missing required keyword `{key}`")))
    }

    pub fn opt_float(&self, key: &str) -> Result<Option<f64>> {
        match self.value_token(key, 0)? {
            Some(t) => Ok(Some(self.parse_float(key, t)?)),
            None => Ok(None),
        }
    }

    pub fn float(&self, key: &str) -> Result<f64> {
        self.opt_float(key)?
            .ok_or_else(|| self.error(format!("missing required keyword `{key}`")))
    }

    pub fn opt_string(&self, key: &str) -> Result<Option<String>> {
        Ok(self.value_token(key, 0)?.map(str::to_string))
    }

    /// The token right after the keyword token `key` (e.g. `domain 3d` -> "3d").
    fn array_len(&self, key: &str) -> Result<Option<(usize, usize)>> {
        let Some(i) = self.find(key) else {
            return Ok(None);
        };
        let n_tok = self.value_token(key, 0)?.unwrap_or("");
        let n = self.parse_int(key, n_tok)?;
        if n < 0 {
            return Err(self.error(format!(
                "`{key}` array size must not be negative, found {n}"
            )));
        }
        let n = n as usize;
        if i + 2 + n > self.tokens.len() {
            return Err(self.error(format!(
                "`{key}` announces {n} values but only {} follow",
                self.tokens.len() - i - 2
            )));
        }
        self.mark(i + 2, n);
        Ok(Some((i + 2, n)))
    }

    /// The `n` values of array `key` from token `start`. A keyword where a value should be means
    /// the announced count is too large: say so rather than "expects a number, found `nodes`".
    fn array_values<T>(
        &self,
        key: &str,
        start: usize,
        n: usize,
        parse: impl Fn(&str) -> Result<T>,
    ) -> Result<Vec<T>> {
        let values = &self.tokens[start..start + n];
        // NaN and infinities spelt out are not numbers an input may hold.
        let non_finite = |t: &str| {
            let l = t.trim_start_matches(['+', '-']).to_ascii_lowercase();
            matches!(l.as_str(), "nan" | "inf" | "infinity")
        };
        if let Some(t) = values.iter().find(|t| non_finite(t)) {
            return Err(self.error(format!("`{key}` expects finite numbers, found `{t}`")));
        }
        if let Some(k) = values.iter().position(|t| {
            t.starts_with(|c: char| c.is_ascii_alphabetic()) && parse_f64(t).is_none()
        }) {
            return Err(self.error(format!(
                "`{key}` announces {n} values but only {k} follow before `{}`",
                values[k]
            )));
        }
        values.iter().map(|t| parse(t)).collect()
    }

    /// A count `k` after `key` and k (tag, number) pairs: OOFEM's `conditions 2 u 0.1 v 3`.
    pub fn opt_tagged_values(&self, key: &str) -> Result<Option<Vec<(String, f64)>>> {
        let Some(i) = self.find(key) else {
            return Ok(None);
        };
        let n_tok = self.value_token(key, 0)?.unwrap_or("");
        let k = usize::try_from(self.parse_int(key, n_tok)?)
            .map_err(|_| self.error(format!("`{key}` count must not be negative")))?;
        if i + 2 + 2 * k > self.tokens.len() {
            return Err(self.error(format!(
                "`{key}` announces {k} (kind, value) pairs but only {} tokens follow",
                self.tokens.len() - i - 2
            )));
        }
        self.mark(i + 2, 2 * k);
        self.tokens[i + 2..i + 2 + 2 * k]
            .chunks(2)
            .map(|pair| Ok((pair[0].clone(), self.parse_float(key, &pair[1])?)))
            .collect::<Result<Vec<_>>>()
            .map(Some)
    }

    pub fn opt_int_array(&self, key: &str) -> Result<Option<Vec<i64>>> {
        let Some((start, n)) = self.array_len(key)? else {
            return Ok(None);
        };
        self.array_values(key, start, n, |t| self.parse_int(key, t))
            .map(Some)
    }

    pub fn int_array(&self, key: &str) -> Result<Vec<i64>> {
        self.opt_int_array(key)?
            .ok_or_else(|| self.error(format!("missing required keyword `{key}`")))
    }

    pub fn opt_float_array(&self, key: &str) -> Result<Option<Vec<f64>>> {
        let Some((start, n)) = self.array_len(key)? else {
            return Ok(None);
        };
        self.array_values(key, start, n, |t| self.parse_float(key, t))
            .map(Some)
    }

    pub fn float_array(&self, key: &str) -> Result<Vec<f64>> {
        self.opt_float_array(key)?
            .ok_or_else(|| self.error(format!("missing required keyword `{key}`")))
    }

    /// A range list `{1 (3 5) 8}` expanded to its integers; more than `limit` entries (the number
    /// of things it can name) is an error.
    pub fn opt_range_list(&self, key: &str, limit: usize) -> Result<Option<Vec<i64>>> {
        let Some(t) = self.value_token(key, 0)? else {
            return Ok(None);
        };
        let bad = || {
            self.error(format!(
                "`{key}` expects a range list like {{1 (3 5) 8}}, found `{t}`"
            ))
        };
        let inner = t
            .strip_prefix('{')
            .and_then(|s| s.strip_suffix('}'))
            .ok_or_else(bad)?;
        let spaced = inner.replace('(', " ( ").replace(')', " ) ");
        let mut words = spaced.split_whitespace();
        let mut out = Vec::new();
        while let Some(w) = words.next() {
            if w == "(" {
                let lo = words
                    .next()
                    .and_then(|s| s.parse::<i64>().ok())
                    .ok_or_else(bad)?;
                let hi = words
                    .next()
                    .and_then(|s| s.parse::<i64>().ok())
                    .ok_or_else(bad)?;
                if words.next() != Some(")") || hi < lo {
                    return Err(bad());
                }
                if (hi - lo) as u64 + out.len() as u64 >= limit as u64 {
                    return Err(self.error(format!(
                        "`{key}` names more than the {limit} entities there are"
                    )));
                }
                out.extend(lo..=hi);
            } else {
                out.push(w.parse::<i64>().map_err(|_| bad())?);
            }
        }
        Ok(Some(out))
    }

    /// The record number (token 2), which must be a positive integer.
    pub fn number(&self) -> Result<usize> {
        self.mark(1, 1);
        let t = self
            .tokens
            .get(1)
            .ok_or_else(|| self.error("missing record number after the keyword"))?;
        match t.parse::<i64>() {
            Ok(v) if v > 0 => Ok(v as usize),
            _ => Err(self.error(format!(
                "record number must be a positive integer, found `{t}`"
            ))),
        }
    }

    /// Tokens that no field lookup consumed (for the "unread tokens" warning).
    pub fn unread(&self) -> Vec<&str> {
        let used = self.used.borrow();
        self.tokens
            .iter()
            .zip(used.iter())
            .filter(|(_, u)| !**u)
            .map(|(t, _)| t.as_str())
            .collect()
    }
}

/// Parse a whole token as f64 (C `strtod` semantics: `1.e-4`, `1e8`, `.5`, `-0.`), no trailing junk.
pub fn parse_f64(t: &str) -> Option<f64> {
    let v: f64 = t.parse().ok().or_else(|| {
        // Rust rejects "1.e-4" style mantissas ending in '.', C accepts them.
        let fixed = t.replacen(".e", ".0e", 1).replacen(".E", ".0E", 1);
        fixed.parse().ok()
    })?;
    let lower = t.to_ascii_lowercase();
    if lower.contains("inf") || lower.contains("nan") {
        return None;
    }
    Some(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;
    use std::sync::Arc;

    fn rec(s: &str) -> Record {
        Record::new(Line {
            file: Arc::new(PathBuf::from("t.in")),
            line: 3,
            text: s.into(),
        })
    }

    #[test]
    fn arrays_ranges_and_floats_parse_like_oofem() {
        let r = rec("Set 2 noderanges {(1 3) 7} nodes 2 4 5 coords 3 1.e-4 2 .5");
        assert_eq!(
            r.opt_range_list("noderanges", 10).unwrap().unwrap(),
            vec![1, 2, 3, 7]
        );
        assert_eq!(r.int_array("nodes").unwrap(), vec![4, 5]);
        assert_eq!(r.float_array("coords").unwrap(), vec![1e-4, 2.0, 0.5]);
        assert_eq!(r.unread(), vec!["set", "2"]);
        assert!(r.opt_range_list("noderanges", 2).is_err());
    }

    #[test]
    fn short_array_is_an_error_with_line() {
        let r = rec("node 1 coords 3 0.0 1.0");
        let e = r.float_array("coords").unwrap_err().to_string();
        assert!(e.starts_with("t.in:3:"), "{e}");
        assert!(e.contains("announces 3 values but only 2 follow"), "{e}");
        let r = rec("n2spenaltycontact 5 nodeset 3 5 6 segmentset 1 1");
        let e = r.int_array("nodeset").unwrap_err().to_string();
        assert!(
            e.contains("`nodeset` announces 3 values but only 2 follow before `segmentset`"),
            "{e}"
        );
    }
}
