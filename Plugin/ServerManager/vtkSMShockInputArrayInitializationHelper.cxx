#include "vtkSMShockInputArrayInitializationHelper.h"

#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkObjectFactory.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"
#include "vtkPVXMLElement.h"
#include "vtkSMArrayListDomain.h"
#include "vtkSMInputProperty.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMStringVectorProperty.h"

#include <cstdlib>
#include <string>

vtkStandardNewMacro(vtkSMShockInputArrayInitializationHelper);

namespace
{
// Whether the domain offers the array (association, name) of a 5-element
// SetInputArrayToProcess property.
bool Offers(vtkSMArrayListDomain* domain, int association, const std::string& name)
{
  for (unsigned int i = 0; i < domain->GetNumberOfStrings(); ++i)
  {
    if (name == domain->GetString(i) && association == domain->GetFieldAssociation(i))
    {
      return true;
    }
  }
  return false;
}

/**
 * Whether the array (association, name) of the input's data information plays
 * a role other than a signal: normals, texture coordinates, tangents, ids. A
 * default never takes those (advected normals stop being unit normals).
 */
bool HasOtherRole(vtkPVDataInformation* information, int association, const std::string& name)
{
  vtkPVDataSetAttributesInformation* attributes = association == vtkDataObject::FIELD_ASSOCIATION_CELLS
    ? information->GetCellDataInformation()
    : information->GetPointDataInformation();
  if (!attributes)
  {
    return false;
  }
  for (int role : { vtkDataSetAttributes::NORMALS, vtkDataSetAttributes::TCOORDS, vtkDataSetAttributes::TANGENTS,
         vtkDataSetAttributes::GLOBALIDS, vtkDataSetAttributes::PEDIGREEIDS })
  {
    vtkPVArrayInformation* array = attributes->GetAttributeInformation(role);
    if (array && array->GetName() && name == array->GetName())
    {
      return true;
    }
  }
  return false;
}
}

void vtkSMShockInputArrayInitializationHelper::PostInitializeProxy(
  vtkSMProxy* proxy, vtkPVXMLElement* xml, vtkMTimeType vtkNotUsed(initializationTimeStamp))
{
  const char* key = xml ? xml->GetAttributeOrDefault("property", "SelectInputArray") : "SelectInputArray";
  auto* array = vtkSMStringVectorProperty::SafeDownCast(proxy->GetProperty(key));
  auto* inputProperty = vtkSMInputProperty::SafeDownCast(proxy->GetProperty("Input"));
  if (!array || array->GetNumberOfElements() != 5 || !inputProperty ||
    inputProperty->GetNumberOfProxies() == 0)
  {
    return;
  }
  auto* input = vtkSMSourceProxy::SafeDownCast(inputProperty->GetProxy(0));
  auto* domain = array->FindDomain<vtkSMArrayListDomain>();
  if (!input || !domain)
  {
    return;
  }
  const std::string name = array->GetElement(4) ? array->GetElement(4) : "";
  const int association = array->GetElement(3) ? std::atoi(array->GetElement(3)) : -1;
  const bool chosenAfterInput = array->GetMTime() > inputProperty->GetMTime();
  if (!name.empty() && chosenAfterInput)
  {
    return;
  }
  // The domain lists the arrays of the input's data information, which is
  // empty until the input has run.
  input->UpdatePipeline();
  domain->Update(nullptr);
  if (!name.empty() && Offers(domain, association, name))
  {
    return;
  }
  array->ResetToDomainDefaults();
  // The domain's default is the active scalars, else its first array: when that
  // is, say, the Normals of a mesh without scalars, take the first array with
  // no other role instead, or none (the filter then asks for an array).
  vtkPVDataInformation* information =
    input->GetDataInformation(inputProperty->GetOutputPortForConnection(0));
  const std::string chosen = array->GetElement(4) ? array->GetElement(4) : "";
  const int chosenAssociation = array->GetElement(3) ? std::atoi(array->GetElement(3)) : -1;
  if (!information || chosen.empty() || !HasOtherRole(information, chosenAssociation, chosen))
  {
    return;
  }
  for (unsigned int i = 0; i < domain->GetNumberOfStrings(); ++i)
  {
    const int where = domain->GetFieldAssociation(i);
    if ((where == vtkDataObject::FIELD_ASSOCIATION_POINTS || where == vtkDataObject::FIELD_ASSOCIATION_CELLS) &&
      !HasOtherRole(information, where, domain->GetString(i)))
    {
      array->SetElement(3, std::to_string(where).c_str());
      array->SetElement(4, domain->GetString(i));
      return;
    }
  }
  array->SetElement(4, ""); // no array to sharpen: the filter says so and names the fix
}

void vtkSMShockInputArrayInitializationHelper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
