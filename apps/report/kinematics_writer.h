#pragma once
/// @file
/// The writer of the kinematics table (apps/study/kinematics_table.h): its JSON object, its
/// text in the paper's units or SI, its CSV and its columns in SI.

#include "apps/report/command_output.h"
#include "apps/study/kinematics_table.h"

namespace needle {

struct KinematicsWriting {
  bool json = false;        ///< the JSON object (else the text)
  bool csv = false;         ///< the CSV file's content too
  bool paper_units = true;  ///< text in mm, dcm/s, m/s² (else m, m/s, m/s², m/s³)
};

CommandOutput WriteKinematics(const KinematicsTable& table, const KinematicsWriting& writing);

}  // namespace needle
