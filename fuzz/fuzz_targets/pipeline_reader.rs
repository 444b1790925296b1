#![no_main]
//! Fuzzes the pipeline reader: arbitrary bytes as a pipeline file. Reading never panics and
//! a refusal is located inside the file; a file that reads and plans (every tool a
//! stand-in) holds no control character in any word, and its dry run, Makefile and Slurm
//! scripts, run by `sh` and `make`, run exactly the plan and nothing else (no `CANARY`).

#[path = "pipeline_common.rs"]
#[allow(dead_code)] // each target uses only some of the checks
mod pipeline_common;

use libfuzzer_sys::fuzz_target;
use pipeline_common::{Sandbox, assert_no_control, check_dry_run, check_makefile, check_slurm};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let sandbox = Sandbox::new();
    let Some(pipeline) = pipeline_common::parse(&sandbox, text) else {
        return;
    };
    let Ok(plan) = pipeline.plan_for_single_steps(&sandbox.tools()) else {
        return;
    };
    assert_no_control(&plan);
    check_dry_run(&sandbox, &plan);
    check_makefile(&sandbox, &plan);
    check_slurm(&sandbox, &plan);
});
