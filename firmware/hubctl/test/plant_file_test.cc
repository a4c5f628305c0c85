// The plant file (plant_file.h): each station's domain from the file or from its station file,
// checked so that a plant-wide tool never joins one domain for two stations, never shows a
// station under a name that breaks its topics' names, and says where a file is wrong.
#include "plant_file.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace hubrt::hubctl {
namespace {

using ::testing::HasSubstr;

std::string plant_error_of(const std::string& text, const std::string& name = "plant.yaml") {
  auto plant = load_plant_file_string(text, name);
  EXPECT_FALSE(plant) << "accepted:\n" << text;
  return plant ? "" : plant.error().message;
}

TEST(PlantFile, ReadsTheStationsInFileOrderWithTheirDomains) {
  auto plant = load_plant_file_string(R"(# two cells
stations:
  cell_b: {domain: 11}
  cell_a: {domain: 10}
  Line2_cell7: {domain: 232}
)",
                                      "plant.yaml");
  ASSERT_TRUE(plant) << plant.error().message;
  ASSERT_EQ(plant->stations.size(), 3U);
  EXPECT_EQ(plant->stations[0].name, "cell_b");
  EXPECT_EQ(plant->stations[0].domain_id, 11U);
  EXPECT_EQ(plant->stations[0].line, 3);
  EXPECT_EQ(plant->stations[1].name, "cell_a");
  EXPECT_EQ(plant->stations[1].domain_id, 10U);
  EXPECT_EQ(plant->stations[2].domain_id, 232U);
}

TEST(PlantFile, RefusesWhatWouldMixStationsUpNamingFileAndLine) {
  EXPECT_THAT(plant_error_of("stations: {a: {domain: 10}, b: {domain: 10}}"),
              HasSubstr("domain 10 is also the domain of station 'a'"));
  EXPECT_THAT(plant_error_of("stations:\n  a: {domain: 10}\n  b: {domain: 10}\n"), HasSubstr("plant.yaml:3"));
  EXPECT_THAT(plant_error_of("stations: {a: {domain: 233}}"), HasSubstr("domain"));
  EXPECT_THAT(plant_error_of("stations: {a: {domain: -1}}"), HasSubstr("domain"));
  EXPECT_THAT(plant_error_of("stations: {a: {}}"), HasSubstr("neither a domain nor a station file"));
  EXPECT_THAT(plant_error_of("stations: {a: {domain: 1, host: x}}"), HasSubstr("host"));
  EXPECT_THAT(plant_error_of("stations: {}"), HasSubstr("lists no station"));
  EXPECT_THAT(plant_error_of("cells: {a: {domain: 1}}"), HasSubstr("cells"));
  EXPECT_THAT(plant_error_of("stations: {a: {domain: 1}}\nstations: {b: {domain: 2}}\n"),
              HasSubstr("stations"));
  // Names become the first part of the station's topics: a ROS name token, nothing else.
  for (const char* bad : {"1st", "cell-a", "cell/a", "_a", "cell a", "\"\""}) {
    EXPECT_THAT(plant_error_of(std::string("stations: {") + bad + ": {domain: 1}}"),
                HasSubstr("station name"))
        << bad;
  }
  EXPECT_THAT(plant_error_of("stations: {" + std::string(64, 'a') + ": {domain: 1}}"),
              HasSubstr("station name"));
  std::string many = "stations:\n";
  for (int i = 0; i < 65; ++i) many += "  s" + std::to_string(i) + ": {domain: " + std::to_string(i) + "}\n";
  EXPECT_THAT(plant_error_of(many), HasSubstr("at most 64"));
}

TEST(PlantFile, StationNamesAreRosNameTokens) {
  EXPECT_TRUE(is_station_name("cell_a"));
  EXPECT_TRUE(is_station_name("d10"));
  EXPECT_TRUE(is_station_name(std::string(63, 'x')));
  EXPECT_FALSE(is_station_name(""));
  EXPECT_FALSE(is_station_name("10"));
  EXPECT_FALSE(is_station_name("a.b"));
  EXPECT_FALSE(is_station_name("caf\xc3\xa9"));
}

// A station file (hubctl net-config's) next to the plant file gives its domain; both given, they
// must agree.
class PlantWithStationFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("hubrt-plant-file-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir_ / "stations");
    std::ofstream(dir_ / "stations" / "cell_a.yaml")
        << "domain: 21\nhosts:\n  cell-a-pc: {address: 10.1.0.1, runs: [planner, dock_ecu]}\n";
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  Expected<PlantFile> load(const std::string& text) {
    const auto path = dir_ / "plant.yaml";
    std::ofstream(path) << text;
    return load_plant_file(path.string());
  }

  std::filesystem::path dir_;
};

TEST_F(PlantWithStationFiles, TakesTheDomainFromTheStationFileRelativeToThePlantFile) {
  auto plant = load("stations:\n  cell_a: {network: stations/cell_a.yaml}\n  cell_b: {domain: 22}\n");
  ASSERT_TRUE(plant) << plant.error().message;
  EXPECT_EQ(plant->stations[0].domain_id, 21U);
  EXPECT_EQ(plant->stations[0].network, "stations/cell_a.yaml");
  EXPECT_EQ(plant->stations[1].domain_id, 22U);
  auto agreeing = load("stations: {cell_a: {domain: 21, network: stations/cell_a.yaml}}\n");
  EXPECT_TRUE(agreeing) << agreeing.error().message;
}

TEST_F(PlantWithStationFiles, RefusesADomainThatDiffersFromTheStationFileOrAMissingStationFile) {
  auto differing = load("stations: {cell_a: {domain: 20, network: stations/cell_a.yaml}}\n");
  ASSERT_FALSE(differing);
  EXPECT_THAT(differing.error().message, HasSubstr("20 differs from the domain of its station file"));
  auto missing = load("stations: {cell_a: {network: stations/nope.yaml}}\n");
  ASSERT_FALSE(missing);
  EXPECT_THAT(missing.error().message, HasSubstr("nope.yaml"));
  // Two stations, one domain through their station files.
  auto twice = load("stations:\n  cell_a: {network: stations/cell_a.yaml}\n  cell_b: {domain: 21}\n");
  ASSERT_FALSE(twice);
  EXPECT_THAT(twice.error().message, HasSubstr("domain 21 is also the domain of station 'cell_a'"));
}

TEST(PlantFile, AMissingFileIsNotFound) {
  auto plant = load_plant_file("/nonexistent/plant.yaml");
  ASSERT_FALSE(plant);
  EXPECT_EQ(plant.error().code, ErrorCode::kNotFound);
}

}  // namespace
}  // namespace hubrt::hubctl
