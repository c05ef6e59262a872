// The KernelTimer of a strategy whose run is one dispatch it keeps on the device (the driver's ray
// query, the control): `Dispatch` gives the dispatch's call() and the hit records it left (hits()).
#pragma once
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "strategies/strategy.h"

namespace rtbench {

template <class Dispatch>
class DispatchTimer : public KernelTimer {
public:
    // `first`: the records of the dispatch's first run; `kernel`: the kernel, as errors name it.
    DispatchTimer(VulkanContext& vk, std::unique_ptr<Dispatch> dispatch, std::vector<gpu::HitRecord> first,
                  std::string kernel)
        : vk_(vk), dispatch_(std::move(dispatch)), first_(std::move(first)), kernel_(std::move(kernel)) {}
    // Warm-ups and repetitions recorded into one submission, each timed on its own.
    TimedBatch time(int warmups, int repetitions) override {
        return splitWarmups(vk_.dispatchAll(std::vector(std::size_t(warmups + repetitions), dispatch_->call())), warmups);
    }
    // The same rays get the same answers every time.
    void checkHits() override { expectSameHits(dispatch_->hits(), first_, kernel_.c_str()); }

private:
    VulkanContext& vk_;
    std::unique_ptr<Dispatch> dispatch_;
    std::vector<gpu::HitRecord> first_;
    std::string kernel_;
};

}  // namespace rtbench
