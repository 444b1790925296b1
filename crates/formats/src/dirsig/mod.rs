//! DIRSIG's material files, as its classic material database writes them: the `.mat`
//! material entries (`mat`) and the spectral emissivity curves they name (`ems`). Read
//! only; irsig's own form is the canonical material library.

pub mod ems;
pub mod mat;
