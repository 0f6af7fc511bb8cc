// The list of slip rules: the one place that names them all.
#include <densify/contact/arctangent_slip.h>
#include <densify/contact/coulomb_slip.h>
#include <densify/contact/friction_law.h>

#include <stdexcept>
#include <utility>

namespace densify
{
  namespace
  {
    /// One object of each rule, in the order of slip_rule_names(): the
    /// rules of Densify, then those register_slip_rule() adds.
    std::vector<std::shared_ptr<const SlipRule>> &
    all_rules()
    {
      static std::vector<std::shared_ptr<const SlipRule>> rules = {
        std::make_shared<CoulombSlip>(), std::make_shared<ArctangentSlip>()};
      return rules;
    }
  } // namespace



  std::shared_ptr<const SlipRule>
  slip_rule(const std::string &name)
  {
    for (const auto &rule : all_rules())
      if (rule->name() == name)
        return rule;
    throw std::invalid_argument("unknown friction model '" + name +
                                "' (one of " + slip_rule_names() + ")");
  }



  void
  register_slip_rule(std::shared_ptr<const SlipRule> rule)
  {
    for (const auto &known : all_rules())
      if (known->name() == rule->name())
        throw std::invalid_argument("a friction model named '" + rule->name() +
                                    "' exists already");
    all_rules().push_back(std::move(rule));
  }



  std::string
  slip_rule_names()
  {
    std::string names;
    for (const auto &rule : all_rules())
      names += (names.empty() ? "" : "|") + rule->name();
    return names;
  }
} // namespace densify
