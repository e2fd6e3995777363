//! The virtual robot of SPEC §8: the BiSCARA's whole body at every sample, the scene around it,
//! and the checks a program must pass before it reaches the real robot.
