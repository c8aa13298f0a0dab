//! OOFEM text lexer: logical lines with file/line numbers, comments, continuation, `@include`,
//! and the tokenizer (whitespace, `"..."`, `{...}`, `$...$`; lower-cased outside quotes).

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// One logical input line (after joining `\` continuations).
#[derive(Debug, Clone)]
pub struct Line {
    pub file: Arc<PathBuf>,
    pub line: usize,
    pub text: String,
}

/// Read `path` into logical lines, skipping blank lines and `#` comments (column 1 only) and
/// splicing `@include "file"` lines (paths relative to the including file).
pub fn read_lines(path: &Path) -> Result<Vec<Line>> {
    let mut out = Vec::new();
    read_into(path, &mut out, 0)?;
    Ok(out)
}

fn read_into(path: &Path, out: &mut Vec<Line>, depth: usize) -> Result<()> {
    if depth > 16 {
        return Err(Error::InputFile {
            file: path.display().to_string(),
            msg: "@include nested more than 16 levels (recursive include?)".into(),
        });
    }
    let bytes = std::fs::read(path).map_err(|e| Error::InputFile {
        file: path.display().to_string(),
        msg: format!("cannot read file: {e}"),
    })?;
    let content = String::from_utf8_lossy(&bytes);
    let file = Arc::new(path.to_path_buf());
    let mut pending: Option<(usize, String)> = None;
    for (i, raw) in content.lines().enumerate() {
        let raw = raw.trim_end_matches('\r');
        let (start, mut text) = match pending.take() {
            Some((start, mut acc)) => {
                acc.push(' ');
                acc.push_str(raw);
                (start, acc)
            }
            None => {
                if raw.trim().is_empty() || raw.starts_with('#') {
                    continue;
                }
                (i + 1, raw.to_string())
            }
        };
        if text.ends_with('\\') {
            text.pop();
            pending = Some((start, text));
            continue;
        }
        if let Some(rest) = text.trim_start().strip_prefix("@include") {
            let name = rest.trim().trim_matches('"');
            let inc = path.parent().unwrap_or(Path::new(".")).join(name);
            read_into(&inc, out, depth + 1)?;
            continue;
        }
        out.push(Line {
            file: file.clone(),
            line: start,
            text,
        });
    }
    if let Some((start, text)) = pending {
        out.push(Line {
            file,
            line: start,
            text,
        });
    }
    Ok(())
}

/// Split a record line into tokens. Text outside double quotes is lower-cased; quoted strings
/// lose their quotes; `{...}` and `$...$` groups are single tokens.
pub fn tokenize(text: &str) -> Vec<String> {
    let mut tokens = Vec::new();
    let chars: Vec<char> = text.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
            continue;
        }
        let (close, keep) = match c {
            '"' => (Some('"'), false),
            '{' => (Some('}'), true),
            '$' => (Some('$'), true),
            _ => (None, true),
        };
        let mut tok = String::new();
        if let Some(close) = close {
            i += 1;
            if keep {
                tok.push(c);
            }
            while i < chars.len() && chars[i] != close {
                tok.push(if c == '"' {
                    chars[i]
                } else {
                    chars[i].to_ascii_lowercase()
                });
                i += 1;
            }
            if i < chars.len() {
                if keep {
                    tok.push(close);
                }
                i += 1;
            }
        } else {
            while i < chars.len() && !chars[i].is_whitespace() {
                tok.push(chars[i].to_ascii_lowercase());
                i += 1;
            }
        }
        tokens.push(tok);
    }
    tokens
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn include_splices_lines_and_continuations_join() {
        let dir = std::env::temp_dir().join(format!("hertz-inc-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(
            dir.join("part.in"),
            "# comment\nnode 2 coords 2 \\\n 1.0 0.0\n",
        )
        .unwrap();
        std::fs::write(
            dir.join("main.in"),
            "out\ndesc\nnode 1 coords 2 0 0\n@include \"part.in\"\nlast\n",
        )
        .unwrap();
        let lines = read_lines(&dir.join("main.in")).unwrap();
        let texts: Vec<&str> = lines.iter().map(|l| l.text.as_str()).collect();
        assert_eq!(
            texts,
            vec![
                "out",
                "desc",
                "node 1 coords 2 0 0",
                "node 2 coords 2   1.0 0.0",
                "last"
            ]
        );
        assert!(lines[3].file.ends_with("part.in") && lines[3].line == 2);
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn tokenizer_lowercases_outside_quotes_and_groups_braces() {
        let t = tokenize(r#"Set 1 noderanges {(1 5) 8} filename "A.in" CrossSect 2"#);
        assert_eq!(
            t,
            vec![
                "set",
                "1",
                "noderanges",
                "{(1 5) 8}",
                "filename",
                "A.in",
                "crosssect",
                "2"
            ]
        );
    }
}
