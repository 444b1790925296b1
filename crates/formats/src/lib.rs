//! Every file syntax irsig reads or writes lives here, and nowhere else.
//!
//! Parsers return typed data or a [`ParseError`] that names the file, the line and column
//! and what was expected, and renders as a miette diagnostic with the offending source
//! line underlined.
//!
//! ```
//! use irsig_formats::ParseError;
//! let text = "4\n6\n0.0 0.0 zero\n";
//! let err = ParseError::at_offset("car.obj", text, 12, "expected a number, found `zero`");
//! assert_eq!((err.line, err.column), (3, 9));
//! assert_eq!(err.to_string(), "car.obj:3:9: expected a number, found `zero`");
//! ```

mod error;
pub mod srf;

pub use error::{ParseError, line_column};
