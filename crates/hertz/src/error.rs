//! Error types of the library. Input errors carry the file, line and record text.

use std::path::PathBuf;

/// Where an input error happened: file, 1-based line, and the record text.
#[derive(Debug, Clone)]
pub struct Span {
    pub file: PathBuf,
    pub line: usize,
    pub record: String,
}

impl Span {
    /// The record text, cut to its first 160 characters for messages.
    pub fn short_record(&self) -> String {
        const SHOWN: usize = 160;
        match self.record.char_indices().nth(SHOWN) {
            None => self.record.clone(),
            Some((at, _)) => format!(
                "{} ... ({} more characters)",
                &self.record[..at],
                self.record[at..].chars().count()
            ),
        }
    }
}

/// Everything that can go wrong in hertz.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Malformed or unsupported input; exit code 2.
    #[error("{}:{}: {msg}\n  record: {}", span.file.display(), span.line, span.short_record())]
    Input { span: Span, msg: String },
    /// Input error not tied to one line (e.g. unreadable file, truncated file).
    #[error("{file}: {msg}")]
    InputFile { file: String, msg: String },
    /// The solver failed (singular matrix, non-convergence, inverted element).
    #[error("solver: {0}")]
    Solve(String),
    /// The system is singular (a mechanism); cutting the step cannot help.
    #[error("solver: {0}")]
    Singular(String),
    /// Writing output failed.
    #[error("output: {0}")]
    Output(String),
    /// The observer asked for the analysis to stop (Ctrl-C in the Python module).
    #[error("interrupted")]
    Interrupted,
}

impl Error {
    /// Process exit code for this error: 2 for bad input, 3 for solver failures, 4 for output,
    /// 130 (as for SIGINT) when interrupted.
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Input { .. } | Error::InputFile { .. } => 2,
            Error::Solve(_) | Error::Singular(_) => 3,
            Error::Output(_) => 4,
            Error::Interrupted => 130,
        }
    }
}

pub type Result<T> = std::result::Result<T, Error>;
