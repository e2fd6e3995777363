//! The inter-file and path-CSV readers, and interpolation plus IK of what they accept, on
//! arbitrary bytes: never a panic, never a non-finite number in an accepted sample.
#![no_main]

use biscara::interpolate::{
    CartesianLimits, InterpolationConfig, Interpolator, NoSpeedLimit, Profile, SlowDown,
    read_path_csv,
};
use biscara::joints::JointTrajectory;
use biscara::kinematics::Kinematics;
use biscara::motion::read_jsonl;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let model = Kinematics::default();
    let config = InterpolationConfig {
        dt: 0.01,
        profile: Profile::Trapezoid,
        start: model.home().to_degrees(),
        limits: CartesianLimits {
            rapid_velocity: 500.0,
            rapid_rotation: 360.0,
            acceleration: 5000.0,
            rotation_acceleration: 7200.0,
        },
        grip_time: 0.0,
    };
    // Bound the work of one input: at most 20 000 samples.
    let motions = read_jsonl(data);
    let samples = Interpolator::new(motions, config, NoSpeedLimit, |_: &SlowDown| {}).take(20_000);
    for row in JointTrajectory::new(samples, model) {
        match row {
            Ok(row) => assert!(row.joints.to_array().iter().all(|v| v.is_finite())),
            Err(_) => break,
        }
    }
    for sample in read_path_csv(data).take(20_000) {
        match sample {
            Ok(sample) => assert!(sample.pose.iter().all(|v| v.is_finite())),
            Err(_) => break,
        }
    }
});
