//! Pictures of the BiSCARA in motion (SPEC §8.3): a self-contained HTML viewer of a joint
//! trajectory (`biscara view`) and a MuJoCo model of the robot (`biscara mjcf`).
