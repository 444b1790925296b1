#![no_main]
//! Fuzzes the dry-run back end (`Plan::dry_run_script`): six arbitrary texts put in every place
//! of a two-stage pipeline (a stage's name, a flag and its value, a subcommand word, an
//! output the next stage reads, a sweep variable; `pipeline_common::pipeline_of`). A text
//! holding a control character is refused where the file is read, at its line and column;
//! otherwise the output, run by the program it is for, runs exactly the plan and nothing
//! else (no `CANARY`).

#[path = "pipeline_common.rs"]
#[allow(dead_code)] // each target uses only some of the checks
mod pipeline_common;

use libfuzzer_sys::fuzz_target;
use pipeline_common::{Sandbox, check_dry_run, plan_of};

fuzz_target!(|texts: [String; 6]| {
    let sandbox = Sandbox::new();
    if let Some(plan) = plan_of(&sandbox, &texts) {
        check_dry_run(&sandbox, &plan);
    }
});
