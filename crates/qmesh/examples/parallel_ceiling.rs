//! What this machine gives two threads on work with no sequential part at all: the
//! ceiling a whole pipeline's speed-up can reach (issue 16's 2-thread goal). Prints one
//! JSON line of seconds per kernel for the current thread count (`RAYON_NUM_THREADS`).
//! `bench/parallel_ceiling.py` runs it on 1 and 2 threads, alternating.
//!
//! Kernels: `compute` (a sine per index, no memory traffic), `gather` (random reads
//! over a 256 MB table, as dart lookups in a large map), `fault` (writing 512 MB of
//! fresh memory, as a growing map), `stream` (writing 256 MB already mapped).

use std::time::Instant;

use rayon::prelude::*;

fn timed<R>(f: impl FnOnce() -> R) -> (f64, R) {
    let t = Instant::now();
    let r = f();
    (t.elapsed().as_secs_f64(), r)
}

fn main() {
    let n = 1usize << 25;
    let (compute, s) = timed(|| (0..n).into_par_iter().map(|i| (i as f64).sin()).sum::<f64>());
    let table: Vec<u32> = (0..1u32 << 26).map(|i| i.wrapping_mul(2_654_435_761)).collect();
    let (gather, g) = timed(|| {
        (0..n)
            .into_par_iter()
            .map(|i| u64::from(table[(i.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 38) & ((1 << 26) - 1)]))
            .sum::<u64>()
    });
    let (fault, blocks) = timed(|| (0..16u64).into_par_iter().map(|k| vec![k + 1; 1 << 22]).map(|v| v[7]).sum::<u64>());
    let mut big = vec![0u64; 1 << 25];
    let (stream, ()) = timed(|| {
        big.par_chunks_mut(1 << 16)
            .enumerate()
            .for_each(|(k, c)| c.iter_mut().enumerate().for_each(|(i, x)| *x = (k ^ i) as u64))
    });
    std::hint::black_box((s, g, blocks, big[77]));
    println!(
        "{{\"threads\": {}, \"compute\": {compute:.5}, \"gather\": {gather:.5}, \"fault\": {fault:.5}, \"stream\": {stream:.5}}}",
        rayon::current_num_threads()
    );
}
