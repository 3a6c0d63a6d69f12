// Fuzz targets of imap_vision: the image loader and the stereo calibration
// loader. Both take a file path, so each input is written to a work file
// first.
#pragma once

#include <vector>

#include "fuzz_common.hpp"

namespace imap::fuzz {

// Image loader oracle: load_grey8 either throws InputError (one line) or
// returns a non-empty, continuous CV_8UC1 image whose every pixel can be
// read; nothing else (no cv::Exception, no std::bad_alloc).
Result check_image(const Bytes& file);
// Format-aware mutations: PNG chunks (CRC repaired) and IHDR fields, PNM
// header numbers, BMP header fields, JPEG segment lengths and SOF sizes,
// plus byte edits and splices of other files.
void mutate_image(Rng& rng, Bytes& file, const std::vector<Bytes>& corpus);

// Calibration loader oracle: load_stereo_calib either throws InputError
// (one line) or returns a calibration that satisfies every rule of
// calib.hpp (sizes, finite values, positive focal lengths and image size,
// R a rotation, non-zero baseline); a small one also builds a Rectifier.
Result check_calib(const Bytes& file);
// Text mutations of YAML / XML calibrations: numbers (huge, tiny, NaN,
// inf), matrix rows / cols / dt, keys renamed, dropped or duplicated,
// structure characters, plus byte edits and splices.
void mutate_calib(Rng& rng, Bytes& file, const std::vector<Bytes>& corpus);

}  // namespace imap::fuzz
