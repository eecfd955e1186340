// The settings table (scene/settings.h): what it declares reaches the typed struct through a
// name and a value, and docs/settings.md holds the table it prints.
#include "scene/scene.h"
#include "support.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

using ssgi::InputError;

namespace {

// docs/settings.md holds the table the settings declare (`render --list-settings` prints it).
TEST(Settings, SettingsDocsHoldTheTable) {
    std::ifstream in(ssgi::test::sourcePath("docs/settings.md"));
    const std::string docs((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string begin = "checks that it is this -->\n", end = "<!-- end of the table -->";
    const size_t from = docs.find(begin), to = docs.find(end);
    ASSERT_NE(from, std::string::npos);
    ASSERT_NE(to, std::string::npos);
    EXPECT_EQ(docs.substr(from + begin.size(), to - from - begin.size()), ssgi::settingsMarkdown())
        << "docs/settings.md: paste the output of build/render --list-settings into the table";
}
// A name and a value become the typed member; the table's default is the struct's.
TEST(Settings, OverridesSetTheTypedMembers) {
    const ssgi::Settings s =
        ssgi::withOverrides({}, {{"cache", 0}, {"ao_steps", 7}, {"exposure", 0.5}}, "test");
    EXPECT_FALSE(s.cache);
    EXPECT_EQ(s.ao_steps, 7);
    EXPECT_EQ(s.exposure, 0.5);
    for (const ssgi::SettingRow& row : ssgi::settingTable())
        EXPECT_EQ(row.get(ssgi::Settings{}), row.defaultValue) << row.name;
    EXPECT_THROW(ssgi::withOverrides({}, {{"ao_steps", 1.5}}, "test"), InputError);
    EXPECT_THROW(ssgi::withOverrides({}, {{"ao_stepz", 1}}, "test"), InputError);
}
} // namespace
