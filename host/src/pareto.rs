//! The Pareto front of a set of (cost, error) points: those no other point beats on both.

/// For each point (cost, error), whether no other point has a cost and an error at most its
/// own with at least one of them lower. Lower is better on both axes; to maximise a quality
/// such as PSNR, pass its negation as the error. NaN never dominates and is never on the front.
pub fn front(points: &[(f64, f64)]) -> Vec<bool> {
    points
        .iter()
        .map(|&(cost, error)| {
            !cost.is_nan()
                && !error.is_nan()
                && !points
                    .iter()
                    .any(|&(c, e)| c <= cost && e <= error && (c < cost || e < error))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dominated_points_are_off_the_front() {
        let points = [
            (1.0, 5.0),
            (2.0, 3.0),
            (3.0, 4.0),
            (4.0, 1.0),
            (2.0, 3.0),
            (f64::NAN, 0.0),
        ];
        assert_eq!(front(&points), [true, true, false, true, true, false]);
    }

    #[test]
    fn infinite_quality_counts_as_best() {
        // An identical image has infinite PSNR: as an error, −∞, which nothing beats.
        let points = [(10.0, f64::NEG_INFINITY), (1.0, -40.0), (5.0, -30.0)];
        assert_eq!(front(&points), [true, true, false]);
    }
}
