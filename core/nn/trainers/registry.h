#pragma once
/// The trainers, Adam's losses and its learning-rate schedules by name (docs/design.md §11), as
/// tiny-cuda-nn's "otype" registries: one table each maps the enum to the name the JSON spells
/// (trainerConfigFromJson / toJson, nn/trainer_config_json.h), so that each name is written once and a
/// new trainer, loss or schedule is one more row. The implementations beside it: lm.cpp
/// (trainLevenbergMarquardt), adam.cpp (trainAdam) and sparse_adam.h (the encoding tables' update).

#include <string>
#include <vector>

#include "core/nn/trainer_config.h"

namespace rrf {

/// One trainer type.
struct TrainerTypeInfo {
    TrainerType type;
    const char* name;       ///< "type" as written ("levenberg_marquardt")
    const char* shortName;  ///< also accepted when read and by withType ("lm"); null if none
    std::vector<std::string> keys;  ///< the keys its "trainer" object may have, "type" included
};

/// One name of an enum value (a loss, a schedule).
template <typename E>
struct NamedValue {
    E value;
    const char* name;
};

/// Every trainer type, in the order messages list them (levenberg_marquardt first: the default of a
/// trainer object without "type").
const std::vector<TrainerTypeInfo>& trainerTypes();
/// The row of `type`.
const TrainerTypeInfo& trainerTypeInfo(TrainerType type);
/// The trainer called `name` (its name or short name), or null.
const TrainerTypeInfo* findTrainerType(const std::string& name);
/// Each trainer by its shortest name ({"lm", "adam"}): the values a trainer sweep takes.
std::vector<std::string> trainerShortNames();
/// Those names joined for messages: "lm or adam".
std::string trainerShortNamesText();

/// Adam's losses ("loss") and learning-rate schedules ("schedule"), in the order messages list them.
const std::vector<NamedValue<AdamLoss>>& adamLosses();
const std::vector<NamedValue<LrSchedule>>& lrSchedules();

/// Every trainer's name and short name ("levenberg_marquardt", "lm", "adam"): what a "type" key, a
/// script's "trainer" and JsonReader::choiceOr accept.
std::vector<std::string> trainerTypeNames();
/// The names of a table's rows, for JsonReader::choiceOr and messages.
template <typename E>
std::vector<std::string> valueNames(const std::vector<NamedValue<E>>& table) {
    std::vector<std::string> names;
    for (const NamedValue<E>& v : table) names.push_back(v.name);
    return names;
}
/// The name of `value` in `table` (the first row when absent: tables list every enum value).
template <typename E>
const char* nameOf(const std::vector<NamedValue<E>>& table, E value) {
    for (const NamedValue<E>& v : table)
        if (v.value == value) return v.name;
    return table.front().name;
}
/// The value named `name` in `table` (a name JsonReader::choiceOr accepted from valueNames(table)).
template <typename E>
E valueNamed(const std::vector<NamedValue<E>>& table, const std::string& name) {
    for (const NamedValue<E>& v : table)
        if (name == v.name) return v.value;
    return table.front().value;
}

}  // namespace rrf
