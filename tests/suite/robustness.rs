//! Whatever the file holds, hertz never panics: thousands of deterministic random mutations of
//! valid inputs (truncation, token deletion, token replacement by garbage or huge numbers,
//! duplicated lines) must each end in Ok or in a typed error.

use hertz::app::{run_file, RunOptions};
use std::path::PathBuf;

struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> usize {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 33) as usize
    }
}

const GARBAGE: [&str; 12] = [
    "0",
    "-1",
    "999999999999",
    "1e308",
    "nan",
    "x",
    "{",
    "(1 5)",
    "\"",
    "{(9 1)}",
    "-0.0",
    "4294967297",
];

fn mutate(src: &str, rng: &mut Lcg) -> String {
    let mut lines: Vec<String> = src.lines().map(str::to_string).collect();
    match rng.next() % 4 {
        0 => {
            let keep = rng.next() % (lines.len() + 1);
            lines.truncate(keep);
        }
        1 | 2 => {
            let i = rng.next() % lines.len();
            let mut toks: Vec<String> = lines[i].split_whitespace().map(str::to_string).collect();
            if !toks.is_empty() {
                let j = rng.next() % toks.len();
                if rng.next().is_multiple_of(2) {
                    toks.remove(j);
                } else {
                    toks[j] = GARBAGE[rng.next() % GARBAGE.len()].to_string();
                }
            }
            lines[i] = toks.join(" ");
        }
        _ => {
            let i = rng.next() % lines.len();
            let l = lines[i].clone();
            lines.insert(i, l);
        }
    }
    lines.join("\n") + "\n"
}

#[test]
fn mutated_inputs_never_panic() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/oofem");
    let tmp = std::env::temp_dir().join(format!("hertz-mut-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let mut rng = Lcg(12345);
    let mut n_err = 0;
    let mut total = 0;
    let mut names: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    names.sort();
    for path in names {
        let src = std::fs::read_to_string(&path).unwrap();
        for k in 0..150 {
            let text = mutate(&src, &mut rng);
            let file = tmp.join(format!("m{k}.in"));
            std::fs::write(&file, &text).unwrap();
            let res = std::panic::catch_unwind(|| run_file(&file, &RunOptions::default()));
            match res {
                Ok(Ok(_)) => {}
                Ok(Err(_)) => n_err += 1,
                Err(_) => panic!("panic on a mutation of {}:\n{text}", path.display()),
            }
            total += 1;
        }
    }
    std::fs::remove_dir_all(&tmp).ok();
    assert!(
        n_err > total / 4,
        "the mutations should mostly be rejected ({n_err} of {total})"
    );
}
