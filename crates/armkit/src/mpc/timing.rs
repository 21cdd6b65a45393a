//! Statistics of the QP solve times of a run, kept without allocating per
//! step: a histogram with 0.5 us buckets up to 8 ms, and the exact maximum.
//!
//! ```
//! use armkit::mpc::SolveTimes;
//! use std::time::Duration;
//! let mut times = SolveTimes::new();
//! for us in [10, 20, 30] {
//!     times.record(Duration::from_micros(us));
//! }
//! assert_eq!(times.count(), 3);
//! assert!((times.median_us() - 20.0).abs() <= 0.5);
//! assert_eq!(times.max_us(), 30.0);
//! ```

use std::time::Duration;

/// Bucket width, us.
const BUCKET_US: f64 = 0.5;
/// Number of buckets (the last also holds everything longer).
const BUCKETS: usize = 16_000;

/// Solve-time statistics: median, percentiles and maximum, in microseconds.
#[derive(Clone, Debug, PartialEq)]
pub struct SolveTimes {
    counts: Vec<u32>,
    count: u64,
    max: Duration,
    total: Duration,
}

impl Default for SolveTimes {
    fn default() -> Self {
        Self::new()
    }
}

impl SolveTimes {
    /// Empty statistics (allocates the histogram once).
    pub fn new() -> Self {
        SolveTimes {
            counts: vec![0; BUCKETS],
            count: 0,
            max: Duration::ZERO,
            total: Duration::ZERO,
        }
    }

    /// Adds one solve time. Allocates nothing.
    pub fn record(&mut self, time: Duration) {
        let bucket = ((time.as_secs_f64() * 1e6 / BUCKET_US) as usize).min(BUCKETS - 1);
        self.counts[bucket] = self.counts[bucket].saturating_add(1);
        self.count += 1;
        self.max = self.max.max(time);
        self.total += time;
    }

    /// Number of solves recorded.
    pub fn count(&self) -> u64 {
        self.count
    }

    /// The `p`-quantile (`p` in [0, 1]), us, to the bucket width (0.5 us),
    /// as the middle of its bucket and never above the maximum; 0 when empty.
    pub fn percentile_us(&self, p: f64) -> f64 {
        if self.count == 0 {
            return 0.0;
        }
        let rank = ((self.count - 1) as f64 * p.clamp(0.0, 1.0)).round() as u64;
        let mut seen = 0u64;
        for (b, &c) in self.counts.iter().enumerate() {
            seen += u64::from(c);
            if seen > rank {
                if b == BUCKETS - 1 {
                    return self.max_us();
                }
                return ((b as f64 + 0.5) * BUCKET_US).min(self.max_us());
            }
        }
        self.max_us()
    }

    /// Median solve time, us.
    pub fn median_us(&self) -> f64 {
        self.percentile_us(0.5)
    }

    /// 99th percentile, us.
    pub fn p99_us(&self) -> f64 {
        self.percentile_us(0.99)
    }

    /// Longest solve, us.
    pub fn max_us(&self) -> f64 {
        self.max.as_secs_f64() * 1e6
    }

    /// Mean solve time, us (0 when empty).
    pub fn mean_us(&self) -> f64 {
        if self.count == 0 {
            0.0
        } else {
            self.total.as_secs_f64() * 1e6 / self.count as f64
        }
    }
}
