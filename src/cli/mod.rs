//! Parts of the `hertz` command that are not the library's: what it shows while it works.

pub mod observer;
