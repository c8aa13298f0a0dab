//! The names of a run's output files, and the rule that none of them may be an input file.

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// Where a run writes: `dir/out_name` (the `.out` file, named by the input's first line) and
/// `dir/stem.*` beside it (`stem.k.vtu`, `stem.pvd`, `stem.contact.csv`, `stem.steps.csv`,
/// `stem.newton.csv`).
#[derive(Debug, Clone)]
pub struct OutputNames {
    pub dir: PathBuf,
    pub out_name: String,
    pub stem: String,
}

impl OutputNames {
    /// The names for an input whose first line is `output_name` (`hertz.out` if empty), written
    /// to `dir`.
    pub fn new(dir: PathBuf, output_name: &str) -> Self {
        let out_name = if output_name.is_empty() {
            "hertz.out".to_string()
        } else {
            output_name.to_string()
        };
        let stem = Path::new(&out_name)
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("hertz")
            .to_string();
        OutputNames {
            dir,
            out_name,
            stem,
        }
    }

    /// The `.out` file's path.
    pub fn out_path(&self) -> PathBuf {
        self.dir.join(&self.out_name)
    }

    /// `dir/stem.suffix`, e.g. `suffix` = `pvd`.
    pub fn path(&self, suffix: &str) -> PathBuf {
        self.dir.join(format!("{}.{suffix}", self.stem))
    }

    /// Whether the run could write `path`: the `.out` file, or a `stem.*` file of the run.
    fn could_write(&self, path: &Path) -> bool {
        let Some(name) = path.file_name().and_then(|n| n.to_str()) else {
            return false;
        };
        let out = self.out_path();
        let in_dir = |d: &Path| same_directory(path.parent(), Some(d));
        if out.file_name().and_then(|n| n.to_str()) == Some(name) && in_dir(out.parent().unwrap()) {
            return true;
        }
        let Some(rest) = name.strip_prefix(&format!("{}.", self.stem)) else {
            return false;
        };
        let fixed = ["pvd", "contact.csv", "steps.csv", "newton.csv"].contains(&rest);
        let vtu = rest
            .strip_suffix(".vtu")
            .is_some_and(|k| !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit()));
        (fixed || vtu) && in_dir(&self.dir)
    }

    /// Refuse a run whose outputs would overwrite one of its input files (the input itself when
    /// its first line names it, an included file or a Gmsh mesh): an input error naming both.
    pub fn check_inputs_kept(&self, sources: &[PathBuf]) -> Result<()> {
        for s in sources {
            let resolved = s.canonicalize().unwrap_or_else(|_| s.clone());
            if self.could_write(s) || self.could_write(&resolved) {
                return Err(Error::InputFile {
                    file: sources[0].display().to_string(),
                    msg: format!(
                        "the run would overwrite its input file {} (its outputs are `{}` and \
                         `{}.*`, named by the first line of the input): refusing; change that \
                         line or write elsewhere with -o DIR",
                        s.display(),
                        self.out_name,
                        self.stem
                    ),
                });
            }
        }
        Ok(())
    }
}

/// Whether two directories are the same one (`None` is the current directory).
fn same_directory(a: Option<&Path>, b: Option<&Path>) -> bool {
    let norm = |d: Option<&Path>| {
        let d = match d {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        d.canonicalize().unwrap_or(d)
    };
    norm(a) == norm(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outputs_that_name_an_input_are_refused() {
        let dir = std::env::temp_dir().join(format!("hertz-names-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        let input = dir.join("model.in");
        std::fs::write(&input, "x").unwrap();
        let kept = |out: &str, d: &Path| {
            OutputNames::new(d.to_path_buf(), out).check_inputs_kept(std::slice::from_ref(&input))
        };
        assert!(kept("model.in", &dir).is_err());
        assert!(kept("model.out", &dir).is_ok());
        // The same directory written another way.
        assert!(kept("model.in", &dir.join("sub/..")).is_err());
        assert!(kept("model.in", &dir.join("sub")).is_ok());
        // A `stem.*` output that is the input: stem "model" writes model.1.vtu, model.pvd, ...
        std::fs::write(dir.join("model.pvd"), "x").unwrap();
        let pvd =
            OutputNames::new(dir.clone(), "model.out").check_inputs_kept(&[dir.join("model.pvd")]);
        assert!(pvd.is_err());
        let vtu = OutputNames::new(dir.clone(), "model.out")
            .check_inputs_kept(&[dir.join("model.12.vtu")]);
        assert!(vtu.is_err());
        let other = OutputNames::new(dir.clone(), "model.out")
            .check_inputs_kept(&[dir.join("model.a.vtu")]);
        assert!(other.is_ok());
        std::fs::remove_dir_all(&dir).ok();
    }
}
