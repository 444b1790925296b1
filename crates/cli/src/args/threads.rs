//! `--threads N`: how many things a tool does at once, in every tool that works in
//! parallel: rayon's worker threads (the tracer, the sensor's blur, an EXR's compression,
//! an OBJ's two passes), LOWTRAN7 processes, a pipeline's tools. Every output is the same at
//! any count.

/// `--threads N`, at least 1; every CPU when not given.
#[derive(Debug, Clone, Copy, Default, clap::Args)]
pub struct ThreadsArgs {
    /// Work on at most N threads at once [default: the number of CPUs]; the outputs do not
    /// depend on it.
    #[arg(id = "threads", long = "threads", value_name = "N", value_parser = threads)]
    pub given: Option<usize>,
}

/// `--threads`: a whole number of at least 1.
fn threads(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err(format!(
            "expected a number of threads, 1 or more, found `{s}`"
        )),
    }
}

impl ThreadsArgs {
    /// The count: the one given, else the number of CPUs this process may use.
    #[must_use]
    pub fn count(&self) -> usize {
        self.given.unwrap_or_else(|| {
            std::thread::available_parallelism().map_or(1, std::num::NonZero::get)
        })
    }

    /// A rayon pool of [`Self::count`] threads.
    ///
    /// # Errors
    /// The system refuses the threads.
    pub fn pool(&self) -> miette::Result<rayon::ThreadPool> {
        rayon::ThreadPoolBuilder::new()
            .num_threads(self.count())
            .build()
            .map_err(|e| miette::miette!("cannot start {} worker threads: {e}", self.count()))
    }

    /// Runs `work` on a rayon pool of [`Self::count`] threads, so that everything it does
    /// in parallel (rayon's iterators and joins, an EXR's compression) keeps to the count.
    ///
    /// # Errors
    /// The pool cannot be made, or `work`'s own error.
    pub fn install<R: Send>(
        &self,
        work: impl FnOnce() -> miette::Result<R> + Send,
    ) -> miette::Result<R> {
        self.pool()?.install(work)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn threads_are_one_or_more_and_every_cpu_by_default() {
        assert_eq!(threads("3"), Ok(3));
        for bad in ["0", "-1", "x", ""] {
            assert!(threads(bad).is_err(), "{bad}");
        }
        assert!(ThreadsArgs::default().count() >= 1);
        let two = ThreadsArgs { given: Some(2) };
        assert_eq!(two.install(|| Ok(rayon::current_num_threads())).unwrap(), 2);
    }
}
