//! A pure transport delay in simulation time: what went in `delay` seconds
//! ago comes out now. Used wherever a stage acts on a signal that reaches
//! it late (vision, the vestibular signal, the pursuit drive).

use std::collections::VecDeque;

/// A delay line over one value per tick. The delay is given per call, so a
/// live edit of a latency takes effect at once (shortening it drops the
/// oldest values; lengthening it holds the oldest until enough history
/// has built up).
#[derive(Clone, Debug, Default)]
pub struct DelayLine<T> {
    buf: VecDeque<T>,
}

impl<T: Clone> DelayLine<T> {
    /// An empty line.
    pub fn new() -> Self {
        DelayLine {
            buf: VecDeque::new(),
        }
    }

    /// Push this tick's value and return the one from `delay` seconds ago
    /// at a step of `dt` (rounded to whole ticks; before that much history
    /// exists, the oldest value held). With a zero delay the value itself.
    pub fn push(&mut self, value: T, delay: f64, dt: f64) -> T {
        let ticks = ticks(delay, dt);
        self.buf.push_back(value);
        while self.buf.len() > ticks + 1 {
            self.buf.pop_front();
        }
        self.buf.front().expect("just pushed").clone()
    }

    /// Forget the history (a new signal starts).
    pub fn clear(&mut self) {
        self.buf.clear();
    }
}

/// A delay in whole ticks (never negative; NaN counts as zero).
pub fn ticks(delay: f64, dt: f64) -> usize {
    if delay > 0.0 && dt > 0.0 {
        (delay / dt).round() as usize
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delays_by_whole_ticks_and_holds_the_oldest_at_first() {
        let mut d = DelayLine::new();
        let out: Vec<i32> = (0..6).map(|k| d.push(k, 0.003, 0.001)).collect();
        assert_eq!(out, [0, 0, 0, 0, 1, 2]);
    }

    #[test]
    fn zero_delay_passes_through_and_shortening_takes_effect_at_once() {
        let mut d = DelayLine::new();
        for k in 0..5 {
            d.push(k, 0.004, 0.001);
        }
        assert_eq!(d.push(5, 0.0, 0.001), 5);
        assert_eq!(d.push(6, 0.001, 0.001), 5);
    }
}
