//! A joint trajectory file read row by row, with its errors located in the file.

use std::fmt::Display;
use std::io::BufRead;
use std::path::Path;

use biscara_joints::{JointCsvRow, read_joint_csv};

use crate::{FileError, display_path, located};

/// Reads the joint CSV `input` (the file `path`) row by row into `each`: a row that cannot be
/// read is the error `FILE:LINE:COL: …`, a row `each` refuses `FILE:LINE: …`, and a trajectory
/// without rows `FILE: the trajectory has no rows`. Returns how many rows were read.
pub fn read_joint_rows<E: Display>(
    path: &Path,
    input: impl BufRead,
    mut each: impl FnMut(&JointCsvRow) -> Result<(), E>,
) -> Result<usize, FileError> {
    let mut rows = 0;
    for row in read_joint_csv(input) {
        let row = row.map_err(|err| located(path, err))?;
        each(&row).map_err(|err| located(path, format_args!("{}: {err}", row.line)))?;
        rows += 1;
    }
    if rows == 0 {
        return Err(FileError::NoRows { path: display_path(path) });
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str = "t_s,theta1_rad,theta2_rad,theta3_rad,d4_mm\n";

    #[test]
    fn rows_are_read_and_their_errors_located() {
        let path = Path::new("traj.csv");
        let text = format!("{HEADER}0,0,0,0,0\n0.001,0,0,0,1\n");
        let mut times = Vec::new();
        let rows = read_joint_rows(path, text.as_bytes(), |row| {
            times.push(row.t);
            Ok::<(), String>(())
        });
        assert_eq!((rows.unwrap(), times), (2, vec![0.0, 0.001]));
        let refused = read_joint_rows(path, text.as_bytes(), |row| match row.line {
            3 => Err("does not assemble"),
            _ => Ok(()),
        });
        assert_eq!(refused.unwrap_err().to_string(), "traj.csv:3: does not assemble");
        let bad = format!("{HEADER}0,0,x,0,0\n");
        let err = read_joint_rows(path, bad.as_bytes(), |_| Ok::<(), String>(())).unwrap_err();
        assert!(err.to_string().starts_with("traj.csv:2:"), "{err}");
        let err = read_joint_rows(path, HEADER.as_bytes(), |_| Ok::<(), String>(())).unwrap_err();
        assert_eq!(err.to_string(), "traj.csv: the trajectory has no rows");
    }
}
