//! DIRSIG's material files, as its classic material database writes them: the `.mat`
//! material entries (`mat`), the spectral emissivity curves they name (`ems`), and a
//! `Therm` temperature solver's block converted to irsig's thermal record (`therm`). Read
//! only; irsig's own form is the canonical material library.

pub mod ems;
pub mod mat;
pub mod therm;
