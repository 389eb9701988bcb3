//! Wall-clock timing by the median of repeated runs, with the contenders interleaved run by
//! run, so that a machine that speeds up or slows down during the measurement affects them all
//! alike. Compare only times taken in the same call.

use std::time::Instant;

/// The environment variable and value under which commands leave wall-clock times out of what
/// they print: as `obscura book` runs them, whose figures are those that come out the same on
/// every run.
pub const TIMES_OMITTED: (&str, &str) = ("OBSCURA_TIMES", "omit");

/// Whether commands print wall-clock times (not under [`TIMES_OMITTED`]).
#[must_use]
pub fn shown() -> bool {
    std::env::var_os(TIMES_OMITTED.0).is_none_or(|value| value != TIMES_OMITTED.1)
}

/// The text `time` makes where times are shown, and nothing where they are not.
#[must_use]
pub fn or_omitted(time: impl FnOnce() -> String) -> String {
    if shown() { time() } else { String::new() }
}

/// Runs each task `runs` times (at least once), round-robin, and returns each task's median
/// time in milliseconds.
pub fn interleaved_median_ms(runs: usize, tasks: &[&dyn Fn()]) -> Vec<f64> {
    let mut times = vec![Vec::with_capacity(runs.max(1)); tasks.len()];
    for _ in 0..runs.max(1) {
        for (task, times) in tasks.iter().zip(&mut times) {
            let start = Instant::now();
            task();
            times.push(start.elapsed().as_secs_f64() * 1e3);
        }
    }
    times.into_iter().map(median).collect()
}

/// Single-thread frame times of `renders`, in ms: the medians of `runs` interleaved renders.
pub fn frame_ms(runs: u16, renders: &[Box<dyn crate::render::AnyFormat>]) -> Vec<f64> {
    let tasks: Vec<Box<dyn Fn() + '_>> = renders
        .iter()
        .map(|p| -> Box<dyn Fn() + '_> { Box::new(move || drop(p.render(1, None))) })
        .collect();
    let task_refs: Vec<&dyn Fn()> = tasks.iter().map(|task| &**task).collect();
    interleaved_median_ms(usize::from(runs), &task_refs)
}

fn median(mut times: Vec<f64>) -> f64 {
    times.sort_by(f64::total_cmp);
    let mid = times.len() / 2;
    if times.len().is_multiple_of(2) {
        (times[mid - 1] + times[mid]) / 2.0
    } else {
        times[mid]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_every_task_round_robin() {
        let order = std::cell::RefCell::new(Vec::new());
        let a = || order.borrow_mut().push('a');
        let b = || order.borrow_mut().push('b');
        let times = interleaved_median_ms(3, &[&a, &b]);
        assert_eq!(times.len(), 2);
        assert_eq!(order.into_inner(), ['a', 'b', 'a', 'b', 'a', 'b']);
    }

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(vec![5.0, 1.0, 3.0]), 3.0);
        assert_eq!(median(vec![4.0, 1.0, 3.0, 2.0]), 2.5);
    }
}
