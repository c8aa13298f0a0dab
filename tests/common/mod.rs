//! Helpers shared by the integration tests.

use hertz::model::Model;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Read a model from input text, through a uniquely named temporary file removed afterwards.
pub fn model_from_text(text: &str) -> hertz::error::Result<Model> {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let k = COUNTER.fetch_add(1, Ordering::Relaxed);
    let path = std::env::temp_dir().join(format!("hertz-test-{}-{k}.in", std::process::id()));
    std::fs::write(&path, text).expect("write a temporary input file");
    let read = hertz::input::read_model(&path);
    std::fs::remove_file(&path).ok();
    read.map(|r| r.model)
}
