//! OOFEM text input: lexer with line numbers -> records -> [`Model`](crate::model::Model).

pub mod contact;
pub mod lexer;
pub mod reader;
pub mod record;
pub mod upstream;

pub use reader::{read_model, read_model_str, read_model_warning, ReadResult};
