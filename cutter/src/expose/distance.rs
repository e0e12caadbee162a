//! The exact Euclidean distance transform of a grid mask (Felzenszwalb and Huttenlocher,
//! "Distance transforms of sampled functions", 2012): the squared distance, in cells, from every
//! cell to the nearest marked cell, in two passes of the one-dimensional transform (the lower
//! envelope of parabolas rooted at the marked cells). The window around what hides the focus is
//! the cells within the margin of it: a round margin, not a square one.

/// Squared distance (in cells) from each cell of a `columns` × `rows` grid (cell `(i, j)` at
/// `i * rows + j`) to the nearest cell where `marked` is true; `f64::INFINITY` everywhere when
/// none is.
pub fn squared_distances(marked: &[bool], columns: usize, rows: usize) -> Vec<f64> {
    debug_assert_eq!(marked.len(), columns * rows);
    let mut along_rows = vec![f64::INFINITY; marked.len()];
    let mut line = vec![0.0; rows.max(columns)];
    let mut out = vec![0.0; rows.max(columns)];
    for i in 0..columns {
        for j in 0..rows {
            line[j] = if marked[i * rows + j] {
                0.0
            } else {
                f64::INFINITY
            };
        }
        transform_1d(&line[..rows], &mut out[..rows]);
        along_rows[i * rows..(i + 1) * rows].copy_from_slice(&out[..rows]);
    }
    let mut result = vec![f64::INFINITY; marked.len()];
    for j in 0..rows {
        for i in 0..columns {
            line[i] = along_rows[i * rows + j];
        }
        transform_1d(&line[..columns], &mut out[..columns]);
        for i in 0..columns {
            result[i * rows + j] = out[i];
        }
    }
    result
}

/// `out[q] = min over p of (q − p)² + f[p]`, over the finite `f[p]`; all infinite when none is.
fn transform_1d(f: &[f64], out: &mut [f64]) {
    let sites: Vec<usize> = (0..f.len()).filter(|&q| f[q].is_finite()).collect();
    let Some(&first) = sites.first() else {
        out.fill(f64::INFINITY);
        return;
    };
    // Where the parabola rooted at q starts to lie below the one rooted at p (p < q).
    let meet = |p: usize, q: usize| {
        let (p2, q2) = ((p * p) as f64, (q * q) as f64);
        ((f[q] + q2) - (f[p] + p2)) / (2.0 * (q as f64 - p as f64))
    };
    // The envelope: roots `v[0..=k]`, parabola k lowest on [z[k], z[k + 1]].
    let mut v = vec![first; sites.len()];
    let mut z = vec![f64::INFINITY; sites.len() + 1];
    z[0] = f64::NEG_INFINITY;
    let mut k = 0;
    for &q in &sites[1..] {
        let mut s = meet(v[k], q);
        while s <= z[k] {
            k -= 1;
            s = meet(v[k], q);
        }
        k += 1;
        v[k] = q;
        z[k] = s;
        z[k + 1] = f64::INFINITY;
    }
    let mut k = 0;
    for (q, o) in out.iter_mut().enumerate() {
        while z[k + 1] < q as f64 {
            k += 1;
        }
        let d = q as f64 - v[k] as f64;
        *o = d * d + f[v[k]];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances_match_the_brute_force_answer() {
        let (columns, rows) = (23, 17);
        let mut marked = vec![false; columns * rows];
        for &(i, j) in &[(3, 4), (15, 2), (20, 16), (10, 10), (11, 10)] {
            marked[i * rows + j] = true;
        }
        let d = squared_distances(&marked, columns, rows);
        for i in 0..columns {
            for j in 0..rows {
                let brute = (0..columns * rows)
                    .filter(|&c| marked[c])
                    .map(|c| {
                        let (mi, mj) = ((c / rows) as f64, (c % rows) as f64);
                        (i as f64 - mi).powi(2) + (j as f64 - mj).powi(2)
                    })
                    .fold(f64::INFINITY, f64::min);
                assert_eq!(d[i * rows + j], brute, "cell ({i}, {j})");
            }
        }
        let none = squared_distances(&[false; 12], 3, 4);
        assert!(none.iter().all(|x| x.is_infinite()));
    }
}
