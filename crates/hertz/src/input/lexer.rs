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
    Ok(read_lines_and_sources(path)?.0)
}

/// [`read_lines`], and every file the input consists of: `path`, the files it includes and the
/// Gmsh meshes it splices, in the order first read (the outputs must never overwrite them).
pub fn read_lines_and_sources(path: &Path) -> Result<(Vec<Line>, Vec<PathBuf>)> {
    let mut out = Vec::new();
    let mut sources = Vec::new();
    read_into(path, &mut out, &mut sources, 0)?;
    Ok((out, sources))
}

/// [`read_lines_and_sources`] of input `text` held in memory under the name `name` (messages
/// say `name:line`; `@include` and `@gmsh` paths are relative to `name`'s directory, the
/// current one for a bare name). The sources list the files it splices, not `name`.
pub fn text_lines_and_sources(name: &Path, text: &str) -> Result<(Vec<Line>, Vec<PathBuf>)> {
    let mut out = Vec::new();
    let mut sources = Vec::new();
    let content = decode_text(name, text.as_bytes())?;
    splice_text(name, content, &mut out, &mut sources, 0)?;
    Ok((out, sources))
}

/// The `@gmsh` meshes among `sources` that have no physical group (and so give no set).
pub fn meshes_without_groups(lines: &[Line], sources: &[PathBuf]) -> Vec<PathBuf> {
    sources
        .iter()
        .filter(|p| {
            let converted = PathBuf::from(format!("{} [converted]", p.display()));
            let mut spliced = lines.iter().filter(|l| *l.file == converted).peekable();
            spliced.peek().is_some() && !spliced.any(|l| l.text.starts_with("Set "))
        })
        .cloned()
        .collect()
}

fn read_into(
    path: &Path,
    out: &mut Vec<Line>,
    sources: &mut Vec<PathBuf>,
    depth: usize,
) -> Result<()> {
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
    let content = decode_text(path, &bytes)?;
    if !sources.iter().any(|p| p == path) {
        sources.push(path.to_path_buf());
    }
    splice_text(path, content, out, sources, depth)
}

/// The logical lines of `content`, the text of `path`, with its includes and meshes spliced.
fn splice_text(
    path: &Path,
    content: &str,
    out: &mut Vec<Line>,
    sources: &mut Vec<PathBuf>,
    depth: usize,
) -> Result<()> {
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
        if let Some(rest) = text.trim_start().strip_prefix("@gmsh") {
            let mesh = splice_gmsh(path, start, &text, rest, out)?;
            if !sources.contains(&mesh) {
                sources.push(mesh);
            }
            continue;
        }
        if let Some(rest) = text.trim_start().strip_prefix("@include") {
            let name = rest.trim().trim_matches('"');
            let inc = path.parent().unwrap_or(Path::new(".")).join(name);
            if !inc.is_file() {
                return Err(line_error(
                    path,
                    start,
                    &text,
                    format!("included file {} does not exist", inc.display()),
                ));
            }
            read_into(&inc, out, sources, depth + 1)?;
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

/// An input error at `line` of `path` (a directive line, before records exist).
fn line_error(path: &Path, line: usize, text: &str, msg: String) -> Error {
    Error::Input {
        span: crate::error::Span {
            file: path.to_path_buf(),
            line,
            record: text.trim().to_string(),
        },
        msg,
    }
}

/// `@gmsh "mesh.msh" [plane stress|strain|axisymmetric] [nlgeo]`: the mesh's node, element and set records,
/// as `hertz import` writes them (`nlgeo`: with `nlgeo 1`), in place of the line. They are located in messages as
/// `mesh.msh [converted]:k`, record k of the conversion. Returns the mesh file's path.
fn splice_gmsh(
    path: &Path,
    line: usize,
    text: &str,
    rest: &str,
    out: &mut Vec<Line>,
) -> Result<PathBuf> {
    use crate::mesh::gmsh::{convert, Plane};
    let here = |msg: String| line_error(path, line, text, msg);
    let words = tokenize(rest);
    let Some(name) = words.first() else {
        return Err(here("`@gmsh` needs a mesh file name".into()));
    };
    let mut options: Vec<&str> = words[1..].iter().map(String::as_str).collect();
    let nlgeo = options.last() == Some(&"nlgeo");
    if nlgeo {
        options.pop();
    }
    let plane = match options[..] {
        [] | ["plane", "stress"] => Plane::Stress,
        ["plane", "strain"] => Plane::Strain,
        ["axisymmetric"] => Plane::Axisymmetric,
        ref other => {
            return Err(here(format!(
                "`@gmsh` takes `plane stress`, `plane strain` or `axisymmetric`, then `nlgeo`, \
                 after the file name, found `{}`",
                other.join(" ")
            )))
        }
    };
    let mesh = path
        .parent()
        .unwrap_or(Path::new("."))
        .join(name.trim_matches('"'));
    if !mesh.is_file() {
        return Err(here(format!("mesh file {} does not exist", mesh.display())));
    }
    let mut converted = convert(&mesh, plane)?;
    converted.nlgeo = nlgeo;
    let file = Arc::new(PathBuf::from(format!("{} [converted]", mesh.display())));
    out.extend(
        converted
            .records()
            .into_iter()
            .enumerate()
            .map(|(k, text)| Line {
                file: file.clone(),
                line: k + 1,
                text,
            }),
    );
    Ok(mesh)
}

/// The file's bytes as text: a UTF-8 byte-order mark is skipped; a NUL byte or bytes that are not
/// UTF-8 are an error naming the line (a binary or UTF-16 file, or a Latin-1 character).
fn decode_text<'a>(path: &Path, bytes: &'a [u8]) -> Result<&'a str> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let line_of = |at: usize| 1 + bytes[..at].iter().filter(|&&b| b == b'\n').count();
    let fail = |msg: String| Error::InputFile {
        file: path.display().to_string(),
        msg,
    };
    if let Some(at) = bytes.iter().position(|&b| b == 0) {
        return Err(fail(format!(
            "line {}: NUL byte: this is not a text file (binary, or UTF-16?)",
            line_of(at)
        )));
    }
    std::str::from_utf8(bytes).map_err(|e| {
        let at = e.valid_up_to();
        fail(format!(
            "line {}: byte 0x{:02X} is not UTF-8 text (save the file as UTF-8)",
            line_of(at),
            bytes[at]
        ))
    })
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
