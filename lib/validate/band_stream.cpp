#include "validate/band_stream.hpp"

namespace mf::validate::detail {

BandStream::BandStream(const BandReader& reader, const InputFile& in, int band_rows, int row_samples,
                       std::function<void(int, int, Samples)> on_band, bool lockstep)
    : on_band_(std::move(on_band)), row_samples_(row_samples), free_run_(!lockstep) {
    thread_ = std::thread(&BandStream::run, this, reader, in, band_rows);
}

BandStream::~BandStream() { finish(); }

void BandStream::run(const BandReader& reader, const InputFile& in, int band_rows) {
    std::string err;
    ImageInfo info;
    bool ok = false;
    try {
        bool shape_changed = false;
        ok = reader(in, band_rows, info, err, [&](int y0, int rows, Samples px) {
            // The header the caller planned with must match what the reader delivers, or every
            // row offset below would be wrong.
            if (shape_changed || info.width * info.channels != row_samples_) {
                shape_changed = true;
                return;
            }
            on_band_(y0, rows, px);
            std::unique_lock lk(m_);
            if (free_run_) return;
            band_ = px;
            y0_ = y0;
            rows_ = rows;
            has_band_ = true;
            cv_.notify_all();
            cv_.wait(lk, [this] { return !has_band_ || free_run_; });
            has_band_ = false;
        });
        if (shape_changed && ok) {
            ok = false;
            err = in.display + ": the file changed while it was being validated (header " + std::to_string(info.width) +
                  "x" + std::to_string(info.height) + "x" + std::to_string(info.channels) +
                  " differs from the one read before)";
        }
    } catch (const std::exception& e) {
        // A reader must not throw (image.hpp), but a thread must never let one escape.
        ok = false;
        err = in.display + ": " + e.what();
    }
    std::lock_guard lk(m_);
    ok_ = ok;
    error_ = err;
    info_ = info;
    done_ = true;
    has_band_ = false;
    cv_.notify_all();
}

Samples BandStream::row(int r) {
    std::unique_lock lk(m_);
    for (;;) {
        if (has_band_) {
            if (r >= y0_ && r < y0_ + rows_)
                return band_ + static_cast<size_t>(r - y0_) * static_cast<size_t>(row_samples_);
            if (r < y0_) return {};  // rows must not go backwards
            has_band_ = false;       // past this band: release it to the reader
            cv_.notify_all();
        }
        if (done_) return {};
        cv_.wait(lk, [this] { return has_band_ || done_; });
    }
}

void BandStream::finish() {
    {
        std::lock_guard lk(m_);
        free_run_ = true;
        has_band_ = false;
        cv_.notify_all();
    }
    if (thread_.joinable()) thread_.join();
}

}  // namespace mf::validate::detail
