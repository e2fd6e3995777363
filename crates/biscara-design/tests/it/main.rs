//! Integration tests of biscara-design: the sweep's indices against an independent brute-force
//! evaluation.

mod brute_force;
