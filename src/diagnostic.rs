//! Error messages for a terminal: `error: file:line: message`, then the offending record with a
//! caret under the token the message names (rendered by miette).

use hertz::error::{Error, Span};
use miette::{GraphicalReportHandler, GraphicalTheme, MietteSpanContents, SourceCode, SourceSpan};

/// The record text of an input error, shown at its line of the file.
#[derive(Debug)]
struct RecordSource {
    name: String,
    line: usize,
    text: String,
}

impl SourceCode for RecordSource {
    fn read_span<'a>(
        &'a self,
        _span: &SourceSpan,
        _before: usize,
        _after: usize,
    ) -> Result<Box<dyn miette::SpanContents<'a> + 'a>, miette::MietteError> {
        Ok(Box::new(MietteSpanContents::new_named(
            self.name.clone(),
            self.text.as_bytes(),
            (0..self.text.len()).into(),
            self.line.saturating_sub(1),
            0,
            1,
        )))
    }
}

#[derive(Debug, thiserror::Error, miette::Diagnostic)]
#[error("{message}")]
struct RecordDiagnostic {
    message: String,
    #[source_code]
    src: RecordSource,
    #[label("{label}")]
    at: SourceSpan,
    label: String,
}

/// Where in the record the message points: the last token it quotes in backticks that the record
/// contains (`found \`4.o\``), else the record keyword.
fn locate(record: &str, msg: &str) -> (usize, usize) {
    let lower = record.to_ascii_lowercase();
    let quoted = msg.split('`').skip(1).step_by(2);
    let mut best = None;
    for q in quoted {
        let q = q.to_ascii_lowercase();
        if q.is_empty() {
            continue;
        }
        let mut from = 0;
        while let Some(i) = lower[from..].find(&q) {
            let at = from + i;
            let end = at + q.len();
            let bounded = (at == 0 || lower.as_bytes()[at - 1].is_ascii_whitespace())
                && (end == lower.len() || lower.as_bytes()[end].is_ascii_whitespace());
            if bounded {
                best = Some((at, q.len()));
                break;
            }
            from = at + 1;
        }
    }
    best.unwrap_or_else(|| (0, record.find(' ').unwrap_or(record.len())))
}

/// The record of `span` with a caret under what `msg` names, as miette draws it.
pub fn snippet(span: &Span, msg: &str, color: bool) -> String {
    let text = span.short_record();
    let (at, len) = locate(&text, msg);
    let diag = RecordDiagnostic {
        message: String::new(),
        src: RecordSource {
            name: span.file.display().to_string(),
            line: span.line,
            text,
        },
        at: (at, len).into(),
        label: "here".into(),
    };
    let theme = if color {
        GraphicalTheme::unicode()
    } else {
        GraphicalTheme::unicode_nocolor()
    };
    let mut out = String::new();
    let handler = GraphicalReportHandler::new_themed(theme).with_wrap_lines(false);
    if handler.render_report(&mut out, &diag).is_err() {
        return String::new();
    }
    // Keep the drawing of the record; the message is printed on the line above it.
    match out.find('╭') {
        Some(i) => {
            let start = out[..i].rfind('\n').map_or(0, |j| j + 1);
            out[start..].trim_end().to_string()
        }
        None => String::new(),
    }
}

/// The full message for `e`: one `error:` line, and for an input error its record drawn below.
pub fn render(e: &Error, color: bool) -> String {
    match e {
        Error::Input { span, msg } => {
            let head = format!("error: {}:{}: {msg}", span.file.display(), span.line);
            match snippet(span, msg, color) {
                s if s.is_empty() => format!("{head}\n  record: {}", span.short_record()),
                s => format!("{head}\n{s}"),
            }
        }
        other => format!("error: {other}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn caret_points_at_the_quoted_token() {
        let span = Span {
            file: "a.in".into(),
            line: 9,
            record: "node 3 coords 2 4.o 1".into(),
        };
        let msg = "`coords` expects a number, found `4.o`";
        assert_eq!(locate(&span.record, msg), (16, 3));
        let s = snippet(&span, msg, false);
        assert!(s.contains("[a.in:9:"), "{s}");
        assert!(s.contains(" 9 │ node 3 coords 2 4.o 1"), "{s}");
        let caret_line = s.lines().find(|l| l.contains('┬')).expect(&s);
        let record_line = s.lines().find(|l| l.contains("4.o")).unwrap();
        assert_eq!(
            caret_line
                .find('┬')
                .map(|i| caret_line[..i].chars().count()),
            record_line
                .find("4.o")
                .map(|i| record_line[..i].chars().count() + 1)
        );
    }
}
