#include "radiosity/active_links.h"

namespace radiosity {

namespace {

bool receiverOrder(const Link& a, const Link& b) {
    return a.receiver < b.receiver;
}

}  // namespace

std::span<const Link> ActiveLinks::of(int node) const {
    index();
    if (node < 0 || node >= static_cast<int>(slot_.size()) || slot_[node] < 0) return {};
    const int i = slot_[node];
    return {links_.data() + start_[i], static_cast<size_t>(start_[i + 1] - start_[i])};
}

size_t ActiveLinks::receiverCount() const {
    index();
    return receivers_.size();
}

bool ActiveLinks::index() const {
    if (!stale_.load(std::memory_order_acquire)) return false;
    std::lock_guard<std::mutex> lock(mutex_);
    if (!stale_.load(std::memory_order_relaxed)) return false;
    reindexLocked();
    stale_.store(false, std::memory_order_release);
    return true;
}

void ActiveLinks::reindexLocked() const {
    // A stable sort of the tail and a stable merge: the same order as a stable sort of
    // all, in linear time when the tail is short.
    const size_t prefix = std::min(sortedPrefix_, links_.size());
    const auto mid = links_.begin() + static_cast<std::ptrdiff_t>(prefix);
    std::stable_sort(mid, links_.end(), receiverOrder);
    std::inplace_merge(links_.begin(), mid, links_.end(), receiverOrder);
    sortedPrefix_ = links_.size();
    receivers_.clear();
    start_.clear();
    int maxReceiver = -1;
    for (size_t i = 0; i < links_.size(); ++i) {
        if (i == 0 || links_[i].receiver != links_[i - 1].receiver) {
            receivers_.push_back(links_[i].receiver);
            start_.push_back(static_cast<int>(i));
            maxReceiver = std::max(maxReceiver, links_[i].receiver);
        }
    }
    start_.push_back(static_cast<int>(links_.size()));
    slot_.assign(static_cast<size_t>(maxReceiver + 1), -1);
    for (size_t i = 0; i < receivers_.size(); ++i) slot_[receivers_[i]] = static_cast<int>(i);
    ++generation_;
}

void ActiveLinks::truncate(size_t n) {
    if (n >= links_.size()) return;
    links_.resize(n);
    sortedPrefix_ = std::min(sortedPrefix_, n);
    stale_ = true;
}

void ActiveLinks::insert(size_t i, const Link& l) {
    i = std::min(i, links_.size());
    links_.insert(links_.begin() + static_cast<std::ptrdiff_t>(i), l);
    sortedPrefix_ = std::min(sortedPrefix_, i);
    stale_ = true;
}

void ActiveLinks::replace(std::vector<Link> links) {
    links_ = std::move(links);
    keepSortedPrefix();
    stale_ = true;
}

void ActiveLinks::keepSortedPrefix() {
    // What is already in order need not be sorted again (a list restored from before a
    // change, or one filtered in order).
    sortedPrefix_ = static_cast<size_t>(
        std::is_sorted_until(links_.begin(), links_.end(), receiverOrder) - links_.begin());
}

std::vector<Link> ActiveLinks::take() {
    std::vector<Link> out;
    out.swap(links_);
    sortedPrefix_ = 0;
    stale_ = true;
    return out;
}

}  // namespace radiosity
