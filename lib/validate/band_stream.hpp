// Internal: one map streamed by mf::read_bands on its own thread, handed to the validating
// thread band by band. read_bands is callback-driven, so reading several maps in lockstep in
// one thread is impossible; each reader thread blocks inside its callback until the consumer
// has moved past the band (the band's memory is read_bands' own buffer: no copy).
#pragma once
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "validate/validate.hpp"

namespace mf::validate::detail {

class BandStream {
public:
    // `on_band` runs on the reader thread for every band, before the consumer sees it (per-map
    // statistics). With `lockstep` false the stream never waits for a consumer.
    BandStream(const BandReader& reader, const InputFile& in, int band_rows, int row_samples,
               std::function<void(int, int, Samples)> on_band, bool lockstep);
    ~BandStream();
    BandStream(const BandStream&) = delete;
    BandStream& operator=(const BandStream&) = delete;

    // Row r (non-decreasing across calls) of the image, or empty when the stream ended early or
    // failed. Valid until the next call.
    Samples row(int r);
    // Lets the reader run to the end without a consumer and waits for it.
    void finish();
    bool ok() const { return ok_; }
    const std::string& error() const { return error_; }
    const ImageInfo& info() const { return info_; }

private:
    // std::thread hands run() its own copies of the arguments, alive until run() returns.
    void run(const BandReader& reader, const InputFile& in, int band_rows);

    std::mutex m_;
    std::condition_variable cv_;
    std::function<void(int, int, Samples)> on_band_;
    int row_samples_ = 0;
    Samples band_;
    int y0_ = 0, rows_ = 0;
    bool has_band_ = false;
    bool free_run_ = false;  // no consumer: never publish, never wait
    bool done_ = false;
    bool ok_ = false;
    std::string error_;
    ImageInfo info_;
    std::thread thread_;
};

}  // namespace mf::validate::detail
