//! The Pareto front of (time, error) points: the settings worth choosing.

/// For each `(time, error)` point, whether no other point is at least as good on both counts and
/// better on one. Points with a NaN are never on the front; equal points are both on it.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<bool> {
    points
        .iter()
        .map(|&(t, e)| {
            !t.is_nan() && !e.is_nan() && !points.iter().any(|&(u, f)| u <= t && f <= e && (u < t || f < e))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dominated_points_are_off_the_front() {
        // (2, 5) is beaten by (1, 4); (3, 1) and (1, 4) trade time for error; (3, 2) loses to (3, 1).
        let points = [(1.0, 4.0), (2.0, 5.0), (3.0, 1.0), (3.0, 2.0), (1.0, 4.0), (f64::NAN, 0.0)];
        assert_eq!(pareto_front(&points), [true, false, true, false, true, false]);
        assert!(pareto_front(&[]).is_empty());
    }
}
