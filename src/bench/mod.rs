//! Benchmarks: the seed experiments and local-method comparisons. (In progress.)
