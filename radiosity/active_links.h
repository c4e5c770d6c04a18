// ActiveLinks: the solver's active links, grouped by receiver, with the index of each
// receiver's run, kept valid by the list itself.
//
// The gather reads the links receiver by receiver (each receiver sums its own links in a
// fixed order, so the result does not depend on the thread count), so the list is kept
// sorted by receiver (stable: the links of one receiver stay in the order they were made)
// with an index of the runs. Refinement, splits for lights and dynamic objects append,
// erase and reinsert links; each structural change marks the index stale, and the next
// read by receiver (of(), runs(), index()) sorts and indexes again. Reading by position
// (operator[], iteration) never reorders: the positions of links appended since the last
// index stay as they were appended until a read by receiver (refinement evaluates the
// visibility of new links by their positions).
//
// Sorting again costs O(n) when only a tail was appended or the list was shrunk in order:
// the list tracks how long a prefix is still sorted and merges the rest in.
//
// Thread safety: reads are safe from many threads. The first read by receiver after a
// change re-indexes under a lock; no thread may change the list meanwhile.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <span>
#include <vector>

#include "radiosity/link.h"

namespace radiosity {

class ActiveLinks {
  public:
    ActiveLinks() = default;
    ActiveLinks(const ActiveLinks&) = delete;
    ActiveLinks& operator=(const ActiveLinks&) = delete;

    // --- Reading by position: never reorders.
    size_t size() const { return links_.size(); }
    bool empty() const { return links_.empty(); }
    const Link& operator[](size_t i) const { return links_[i]; }
    std::vector<Link>::const_iterator begin() const { return links_.begin(); }
    std::vector<Link>::const_iterator end() const { return links_.end(); }
    /// The links in their current order: sorted by receiver up to the last change.
    const std::vector<Link>& all() const { return links_; }

    // --- Reading by receiver: sorts and indexes first if the list changed.
    /// The links that `node` gathers through (empty when none).
    std::span<const Link> of(int node) const;
    /// Runs of one receiver each: receiver(i) gathers through links [start(i), start(i+1)).
    size_t receiverCount() const;
    int receiver(size_t i) const { return receivers_[i]; }
    int start(size_t i) const { return start_[i]; }
    /// Sorts and indexes now if the list changed. Returns whether it did.
    bool index() const;
    /// The whole list, sorted by receiver (indexed first if it changed).
    const std::vector<Link>& byReceiver() const {
        index();
        return links_;
    }
    /// Incremented by every re-index (and never by reading it): what was built on the
    /// runs (a layout of them) is stale when it differs.
    uint64_t generation() const { return generation_; }

    // --- Changes that keep receivers and order: allowed at any time.
    /// A link's fields other than receiver and source (V, F, type, ...).
    Link& mutableAt(size_t i) { return links_[i]; }
    template <class F>
    void forEachMutable(F f) {
        for (Link& l : links_) f(l);
    }

    // --- Structural changes: each marks the index stale.
    void push_back(const Link& l) {
        links_.push_back(l);
        stale_ = true;
    }
    void reserve(size_t n) { links_.reserve(n); }
    void clear() { replace({}); }
    /// Keeps the first n links.
    void truncate(size_t n);
    /// Inserts l at position i.
    void insert(size_t i, const Link& l);
    /// Applies f to every link, which may change its receiver or source (a node renamed).
    template <class F>
    void relabel(F f) {
        for (Link& l : links_) f(l);
        keepSortedPrefix();
        stale_ = true;
    }
    /// Erases the links for which erase(link) is true, keeping the others' order.
    template <class P>
    void eraseIf(P erase) {
        size_t keptInPrefix = 0;
        for (size_t i = 0; i < sortedPrefix_ && i < links_.size(); ++i)
            if (!erase(links_[i])) ++keptInPrefix;
        std::erase_if(links_, erase);
        sortedPrefix_ = keptInPrefix;
        stale_ = true;
    }
    /// Replaces the whole list (sorted again at the next read by receiver).
    void replace(std::vector<Link> links);
    /// Hands the list out, leaving it empty (for a caller that rebuilds it).
    std::vector<Link> take();

  private:
    void reindexLocked() const;
    /// sortedPrefix_ = the longest prefix that is in receiver order.
    void keepSortedPrefix();

    // Mutable: a read by receiver may sort and index a list that changed (see above).
    mutable std::vector<Link> links_;
    mutable std::vector<int> receivers_, start_, slot_;
    mutable size_t sortedPrefix_ = 0;  ///< links_[0, sortedPrefix_) is sorted by receiver
    mutable std::atomic<bool> stale_{true};
    mutable uint64_t generation_ = 0;
    mutable std::mutex mutex_;
};

}  // namespace radiosity
