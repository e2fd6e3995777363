//! The points reader and CL generator (with IK checks) on arbitrary bytes: never a panic.
#![no_main]

use biscara::kinematics::Kinematics;
use biscara::pnp::ClProgram;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let model = Kinematics::default();
    for statement in ClProgram::new(data, &model) {
        if statement.is_err() {
            break;
        }
    }
});
