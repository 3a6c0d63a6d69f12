// Shared pieces of the streaming-testbench tests: a stream setup for the
// firmware on small frames, and frame sources built in the test.
#pragma once

#include <boost/test/unit_test.hpp>
#include <functional>
#include <string>
#include <vector>

#include "imap/firmware/plan.hpp"
#include "imap/firmware/run.hpp"
#include "imap/testbench/stream.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/sequence.hpp"

namespace tbtest {

namespace g = imap::golden;
namespace fw = imap::firmware;
namespace tb = imap::testbench;

// The DP firmware for w x h frames (whole-frame ROI) on `pes` PEs.
inline tb::StreamSetup make_setup(int w, int h, int D, int pes, double fps, double line_us) {
    tb::StreamSetup s;
    s.params.D = D;
    s.roi = {0, 0, w, h};
    s.size = {w, h};
    s.machine.pes = pes;
    s.plan = fw::plan_frame(s.params, s.roi, s.machine);
    s.program = fw::assemble_frame(s.params, s.plan);
    s.timing.fps = fps;
    s.timing.line_us = line_us;
    s.timing.resolve(h);
    return s;
}

// A source from a list of frames (a frame with a non-empty error is bad).
class ListSource : public tb::FrameSource {
  public:
    explicit ListSource(std::vector<tb::SourceFrame> frames) : f_(std::move(frames)) {}
    bool next(tb::SourceFrame& f) override {
        if (i_ >= f_.size()) return false;
        f = f_[i_++];
        return true;
    }
    int count() const override { return static_cast<int>(f_.size()); }
    std::string describe() const override { return "test frames"; }

  private:
    std::vector<tb::SourceFrame> f_;
    size_t i_ = 0;
};

// Frames 0..n-1 of the synthetic sequence `seed`.
inline std::vector<tb::SourceFrame> sequence(uint64_t seed, int w, int h, int n) {
    std::vector<tb::SourceFrame> v;
    for (int k = 0; k < n; ++k) {
        const imap::vision::SequenceFrame s = imap::vision::make_sequence_frame(seed, w, h, k, n);
        tb::SourceFrame f;
        f.index = k;
        f.name = "frame " + std::to_string(k);
        f.left = s.left;
        f.right = s.right;
        f.gt = s.gt;
        v.push_back(f);
    }
    return v;
}

// The same frame on the bare machine core (no SystemC, no streaming): the
// independent reference for the map and the cycle count.
inline fw::FrameResult core_run(const tb::StreamSetup& s, const tb::SourceFrame& f) {
    return fw::run_frame_core(s.plan, s.program, imap::vision::view_of(f.left),
                              imap::vision::view_of(f.right), s.machine);
}

}  // namespace tbtest
