//! The identity machine: every joint is the axis of the same name (3-axis mills and lathes).

use crate::{Joints, KinError, Kinematics};
use stanok_canon::Pose;

/// Joints equal the pose's axes.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Cartesian;

impl Kinematics for Cartesian {
    fn inverse(&self, pose: &Pose) -> Result<Joints, KinError> {
        Ok(pose.to_array())
    }

    fn forward(&self, joints: &Joints) -> Result<Pose, KinError> {
        Ok(Pose::from_array(*joints))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn forward_of_inverse_is_identity(v in prop::array::uniform9(-1e4f64..1e4)) {
            let p = Pose::from_array(v);
            let back = Cartesian.forward(&Cartesian.inverse(&p).unwrap()).unwrap();
            prop_assert_eq!(back, p);
        }
    }
}
