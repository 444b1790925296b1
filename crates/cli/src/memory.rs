//! The memory a process may still take, and a refusal before a large allocation that
//! would not fit: an allocation past it aborts the process (exit 134) and leaves its
//! staged files behind, which no error path can clean up.
//!
//! What may be taken is the least of what Linux states: the kernel's estimate of the
//! memory available without swapping (`MemAvailable`, `/proc/meminfo`), the address space
//! a `ulimit -v` leaves (`/proc/self/limits` less `VmSize`, `/proc/self/status`), and a
//! cgroup v2 limit less its use (`/sys/fs/cgroup/memory.max`, `memory.current`). Where
//! none can be read (another system), nothing is refused.

use std::path::Path;

/// What a process may still allocate, bytes, and the limit that sets it; `None` when no
/// limit can be read.
#[must_use]
pub fn available() -> Option<(u64, &'static str)> {
    let read = |p: &str| std::fs::read_to_string(Path::new(p)).ok();
    let meminfo = read("/proc/meminfo").and_then(|t| field_kib(&t, "MemAvailable:"));
    let address_space = read("/proc/self/limits")
        .and_then(|t| address_space_limit(&t))
        .zip(read("/proc/self/status").and_then(|t| field_kib(&t, "VmSize:")))
        .map(|(limit, used)| limit.saturating_sub(used));
    let cgroup = read("/sys/fs/cgroup/memory.max")
        .and_then(|t| t.trim().parse::<u64>().ok())
        .zip(read("/sys/fs/cgroup/memory.current").and_then(|t| t.trim().parse::<u64>().ok()))
        .map(|(max, used)| max.saturating_sub(used));
    [
        (meminfo, "the memory available (MemAvailable)"),
        (address_space, "the address space `ulimit -v` leaves"),
        (cgroup, "the cgroup's memory.max"),
    ]
    .into_iter()
    .filter_map(|(bytes, what)| Some((bytes?, what)))
    .min_by_key(|&(bytes, _)| bytes)
}

/// A `NAME:   1234 kB` line of a `/proc` file, bytes.
fn field_kib(text: &str, name: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(name))?;
    let kib: u64 = line[name.len()..].split_whitespace().next()?.parse().ok()?;
    kib.checked_mul(1024)
}

/// The soft limit of `Max address space` in `/proc/self/limits`, bytes (`None` when
/// unlimited).
fn address_space_limit(text: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with("Max address space"))?;
    line["Max address space".len()..]
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// Refuses, before anything is allocated, work whose estimate `need_bytes` exceeds what
/// the process may take ([`available`]): the message gives both, `what` needs it, and
/// `way_out`, how to need less.
///
/// # Errors
/// When the estimate does not fit.
pub fn check_fits(need_bytes: u64, what: &str, way_out: &str) -> miette::Result<()> {
    match available() {
        Some((free, limit)) if need_bytes > free => Err(miette::miette!(
            "{what} needs about {} and {limit} is {}: {way_out}",
            gigabytes(need_bytes),
            gigabytes(free)
        )),
        _ => Ok(()),
    }
}

fn gigabytes(bytes: u64) -> String {
    #[allow(clippy::cast_precision_loss)] // for a message, to 0.1 GB
    let gb = bytes as f64 / 1e9;
    format!("{gb:.1} GB")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn proc_fields_are_read_in_bytes() {
        let meminfo = "MemTotal:       24589028 kB\nMemAvailable:   20000000 kB\n";
        assert_eq!(field_kib(meminfo, "MemAvailable:"), Some(20_000_000 * 1024));
        assert_eq!(field_kib(meminfo, "VmSize:"), None);
        let limits = "Limit                     Soft Limit           Hard Limit           Units\n\
                      Max address space         4096000000           unlimited            bytes\n";
        assert_eq!(address_space_limit(limits), Some(4_096_000_000));
        let unlimited =
            "Max address space         unlimited            unlimited            bytes\n";
        assert_eq!(address_space_limit(unlimited), None);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn an_estimate_past_any_machine_is_refused_with_both_figures() {
        let (free, _) = available().expect("Linux states MemAvailable");
        assert!(free > 0);
        let text = check_fits(u64::MAX, "the frame", "trace it in tiles")
            .unwrap_err()
            .to_string();
        assert!(
            text.starts_with("the frame needs about 18446744073.7 GB and ")
                && text.ends_with(": trace it in tiles"),
            "{text}"
        );
        assert!(check_fits(0, "nothing", "").is_ok());
    }
}
