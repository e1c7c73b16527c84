//! What every parallel job shares: a thread pool of the asked size and a
//! progress bar (drawn on standard error, only on a terminal).

/// A thread pool of `jobs` threads (at least one).
pub fn pool(jobs: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.max(1))
        .build()
        .expect("a thread pool of a few threads can be built")
}

/// A progress bar over `len` items, described as `what` ("runs", "scenes",
/// "s simulated"); its message, if set, follows.
pub fn bar(len: u64, what: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(len);
    bar.set_style(
        indicatif::ProgressStyle::with_template(&format!(
            "{{bar:40}} {{pos}}/{{len}} {what}, {{elapsed}} elapsed, eta {{eta}} {{msg}}"
        ))
        .expect("the template is valid"),
    );
    bar
}
