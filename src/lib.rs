//! The `hertz` command line over the `hertz` library: the terminal observer (log lines,
//! progress bar), error rendering with the offending record, plots, `hertz import`'s and
//! `hertz bench`'s arguments. The library prints nothing and depends on none of clap,
//! indicatif, miette or plotters; everything that does lives here.

pub mod bench;
pub mod cli;
pub mod diagnostic;
pub mod import;
pub mod plot;
