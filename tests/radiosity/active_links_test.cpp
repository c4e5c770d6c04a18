// ActiveLinks keeps its receiver index valid by itself: whatever changes the list, a read
// by receiver sees every link of that receiver, in the order the links were made.
#include <gtest/gtest.h>

#include <vector>

#include "radiosity/active_links.h"

using radiosity::ActiveLinks;
using radiosity::Link;

namespace {

Link link(int receiver, int source) {
    Link l;
    l.receiver = receiver;
    l.source = source;
    return l;
}

std::vector<int> sourcesOf(const ActiveLinks& links, int receiver) {
    std::vector<int> out;
    for (const Link& l : links.of(receiver)) out.push_back(l.source);
    return out;
}

}  // namespace

TEST(ActiveLinks, ReadsByReceiverSeeEveryChangeInTheOrderLinksWereMade) {
    ActiveLinks links;
    for (auto [r, s] : {std::pair{3, 10}, {1, 11}, {3, 12}, {2, 13}, {1, 14}})
        links.push_back(link(r, s));
    // Reading by position does not reorder.
    EXPECT_EQ(links[0].receiver, 3);
    EXPECT_EQ(links[4].source, 14);
    EXPECT_EQ(sourcesOf(links, 1), (std::vector<int>{11, 14}));  // stable within a receiver
    EXPECT_EQ(sourcesOf(links, 3), (std::vector<int>{10, 12}));
    EXPECT_TRUE(links.of(7).empty());   // a node with no links
    EXPECT_TRUE(links.of(-1).empty());  // not a node
    EXPECT_EQ(links.receiverCount(), 3u);

    // Appended after an index: the new link joins its receiver's run.
    links.push_back(link(1, 15));
    EXPECT_EQ(sourcesOf(links, 1), (std::vector<int>{11, 14, 15}));
    // Erased in order, inserted at a position, truncated.
    links.eraseIf([](const Link& l) { return l.source == 14; });
    EXPECT_EQ(sourcesOf(links, 1), (std::vector<int>{11, 15}));
    links.insert(0, link(2, 16));
    EXPECT_EQ(sourcesOf(links, 2), (std::vector<int>{16, 13}));
    links.truncate(links.size() - 1);  // the last in receiver order: (3, 12)
    EXPECT_EQ(sourcesOf(links, 3), (std::vector<int>{10}));
    // A receiver renamed (a node's copy takes its links).
    links.relabel([](Link& l) {
        if (l.receiver == 1) l.receiver = 9;
    });
    EXPECT_TRUE(links.of(1).empty());
    EXPECT_EQ(sourcesOf(links, 9), (std::vector<int>{11, 15}));
    // Replaced wholesale, out of order.
    links.replace({link(5, 1), link(4, 2), link(5, 3)});
    EXPECT_EQ(sourcesOf(links, 5), (std::vector<int>{1, 3}));
    EXPECT_EQ(links.receiverCount(), 2u);
}

TEST(ActiveLinks, GenerationChangesOnlyWhenTheListIsIndexedAgain) {
    ActiveLinks links;
    links.push_back(link(0, 1));
    EXPECT_TRUE(links.index());
    const uint64_t g = links.generation();
    EXPECT_FALSE(links.index());  // nothing changed
    links.mutableAt(0).V = 0.5f;  // a field, not the grouping
    (void)links.of(0);
    EXPECT_EQ(links.generation(), g);
    links.push_back(link(0, 2));
    EXPECT_EQ(links.generation(), g);  // reading the generation does not index
    EXPECT_EQ(links.of(0).size(), 2u);
    EXPECT_EQ(links.generation(), g + 1);
}
