//! Every file syntax irsig reads or writes lives here, and nowhere else.
//!
//! Parsers return typed data or a [`ParseError`] that names the file, the line and column
//! and what was expected, and renders as a miette diagnostic with the offending source
//! line underlined.
//!
//! [`legacy`] holds the 1990 formats of the thesis (object, scene, material index, viewing
//! and execute files, and the DIRTRAN tables `.ems .atm .cor .dwr .rsd .rtt`), each with a
//! `parse` and a round-tripping `write`; their spec pages are in `formats/legacy/`.
//!
//! ```
//! use irsig_formats::ParseError;
//! let text = "4\n6\n0.0 0.0 zero\n";
//! let err = ParseError::at_offset("car.obj", text, 12, "expected a number, found `zero`");
//! assert_eq!((err.line, err.column), (3, 9));
//! assert_eq!(err.to_string(), "car.obj:3:9: expected a number, found `zero`");
//! ```

#![deny(clippy::print_stdout, clippy::print_stderr)]
// A ParseError carries its source text for the miette snippet; it is built once, on the
// cold path, so returning it unboxed costs nothing that matters.
#![allow(clippy::result_large_err)]

pub mod canonical;
mod columns;
pub mod dirsig;
mod error;
pub mod file;
pub mod inflate;
pub mod legacy;
pub mod lut;
pub mod mesh;
pub mod nk;
pub mod radtran;
pub mod ron_tree;
pub mod srf;
pub mod time;
pub mod views;
pub mod weather;

pub use error::{ParseError, line_column, offset_of};
