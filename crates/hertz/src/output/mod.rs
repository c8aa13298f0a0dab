//! Results: the OOFEM `.out` file, ParaView VTU/PVD files, `#%BEGIN_CHECK%` rule evaluation.

pub mod check;
pub mod names;
pub mod number;
pub mod outfile;
pub mod vtu;
pub mod writer;

use crate::error::{Error, Result};
use std::path::Path;

/// Write a file whole: to a temporary name in the same directory, then rename.
pub fn write_atomic(path: &Path, content: &[u8]) -> Result<()> {
    write_atomic_parts(path, &[content])
}

/// [`write_atomic`] of the concatenation of `parts` (large files built in pieces are not
/// copied into one buffer first).
pub fn write_atomic_parts(path: &Path, parts: &[&[u8]]) -> Result<()> {
    let tmp = path.with_extension(format!(
        "{}.tmp{}",
        path.extension().and_then(|e| e.to_str()).unwrap_or(""),
        std::process::id()
    ));
    let written = std::fs::File::create(&tmp).and_then(|mut f| {
        use std::io::Write as _;
        parts.iter().try_for_each(|p| f.write_all(p))
    });
    if let Err(e) = written {
        let _ = std::fs::remove_file(&tmp);
        return Err(Error::Output(format!(
            "cannot write {}: {e}",
            tmp.display()
        )));
    }
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        Error::Output(format!(
            "cannot rename {} to {}: {e}",
            tmp.display(),
            path.display()
        ))
    })
}
