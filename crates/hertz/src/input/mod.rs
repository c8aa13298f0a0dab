//! OOFEM text input: lexer with line numbers -> records -> [`Model`](crate::model::Model).

mod conditions;
pub mod contact;
mod cursor;
mod elements;
mod functions;
mod header;
mod keywords;
pub mod lexer;
mod materials;
mod nodes;
pub mod reader;
pub mod record;
mod resolve;
mod sets;
pub mod upstream;

pub use reader::{read_model, read_model_str, read_model_warning, ReadResult};
